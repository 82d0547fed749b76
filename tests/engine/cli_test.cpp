// rockcal-dem as a user runs it: exit codes, files written, nothing written for a bad job.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {

struct CliRun {
  int exit_code;
  std::string out;
};

CliRun run(const std::string& args) {
  const fs::path capture =
      fs::temp_directory_path() / ("rockcal_cli_" + std::to_string(::getpid()) + ".out");
  const std::string cmd =
      std::string(ROCKCAL_DEM) + " " + args + " > " + capture.string() + " 2>/dev/null";
  const int status = std::system(cmd.c_str());
  std::ifstream in(capture);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  fs::remove(capture);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

fs::path temp_dir(const std::string& name) {
  fs::path d =
      fs::temp_directory_path() / ("rockcal_cli_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  return d;
}

}  // namespace

TEST(Cli, InvalidJobExitsTwoNamesTheFieldAndWritesNothing) {
  const fs::path dir = temp_dir("bad");
  fs::create_directories(dir);
  std::ofstream(dir / "job.json")
      << R"({"test": "uct", "material": {"kr": -1, "nu": 0.2}, "bond": {"fr0": 1, "fs0": 1}})";
  const fs::path out = dir / "out";
  const CliRun r = run("run " + (dir / "job.json").string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(nlohmann::json::parse(r.out)["field"], "material.kr");
  EXPECT_FALSE(fs::exists(out));
  std::ofstream(dir / "broken.json") << "{\"test\": ";
  EXPECT_EQ(run("validate " + (dir / "broken.json").string()).exit_code, 2);
  fs::remove_all(dir);
}

TEST(Cli, RunsTheSmallUctExampleAndWritesItsFiles) {
  const fs::path out = temp_dir("uct");
  const CliRun r =
      run(std::string("run ") + ROCKCAL_EXAMPLES + "/uct_small.json --out " + out.string());
  ASSERT_EQ(r.exit_code, 0);
  const auto printed = nlohmann::json::parse(r.out);
  std::ifstream in(out / "result.json");
  const auto stored = nlohmann::json::parse(in);
  EXPECT_EQ(printed, stored);
  EXPECT_GT(stored["peak_load"].get<double>(), 0.0);
  EXPECT_GT(stored["broken_bonds"].get<int>(), 0);
  EXPECT_TRUE(fs::exists(out / "curve.csv"));
  EXPECT_TRUE(fs::exists(out / "breaks.csv"));
  EXPECT_FALSE(fs::exists(out / "result.json.tmp"));
  fs::remove_all(out);
}
