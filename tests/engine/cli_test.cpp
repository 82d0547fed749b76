// rockcal-dem as a user runs it: exit codes, files written, nothing written for a bad job, valid
// JSON on stdout whatever bytes the job file holds, and a stop honoured at any stage.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

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

TEST(Cli, InvalidUtf8InAJobFileStillGivesAJsonErrorAndExitTwo) {
  const fs::path dir = temp_dir("utf8");
  fs::create_directories(dir);
  // The parse error quotes the byte it stopped at; at 64e168e dumping it threw (exit 134).
  std::ofstream(dir / "job.json") << "{\"test\":\"uct\",\"sample\":{\"packing\":\"fc\xff\"}}";
  const CliRun r = run("validate " + (dir / "job.json").string());
  EXPECT_EQ(r.exit_code, 2);
  const auto printed = nlohmann::json::parse(r.out, nullptr, false);  // strict: valid UTF-8 only
  ASSERT_TRUE(printed.is_object()) << r.out;
  EXPECT_EQ(printed["field"], "(root)");
  const std::string error = printed["error"];
  EXPECT_EQ(error.rfind("(root): malformed JSON: [json.exception.parse_error.101]", 0), 0u)
      << error;
  EXPECT_NE(error.find("ill-formed UTF-8 byte"), std::string::npos) << error;
  EXPECT_NE(error.find("\"fc\xef\xbf\xbd"), std::string::npos)
      << "the byte shown as U+FFFD: " << error;
  fs::remove_all(dir);
}

TEST(Cli, DeepNestingAndOverflowingSizesExitTwoNamingTheProblem) {
  const fs::path dir = temp_dir("hostile");
  fs::create_directories(dir);
  {
    std::ofstream deep(dir / "deep.json");
    deep << "{\"test\":\"uct\",\"a\":";
    for (int i = 0; i < 100000; ++i) deep << "{\"a\":";
    deep << 1 << std::string(100001, '}');
  }
  CliRun r = run("validate " + (dir / "deep.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(nlohmann::json::parse(r.out, nullptr, false),
            nlohmann::json({{"error", "(root): JSON nested deeper than 64 levels (the limit)"},
                            {"field", "(root)"}}))
      << r.out.substr(0, 300);
  // inf / inf = NaN slipped past the particle cap at 64e168e: validate said valid, run never ended.
  std::ofstream(dir / "huge.json")
      << R"({"test": "uct", "sample": {"diameter": 1e308, "height": 1e308, "radius": 1e300},)"
      << R"( "material": {"kr": 8000}, "bond": {"fr0": 1, "fs0": 1}})";
  r = run("validate " + (dir / "huge.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(nlohmann::json::parse(r.out, nullptr, false)["field"], "sample.diameter") << r.out;
  fs::remove_all(dir);
}

TEST(Cli, SigtermWhileBuildingThePackingStopsTheRunAtOnce) {
  const fs::path dir = temp_dir("sigterm");
  fs::create_directories(dir / "cache");
  // A random packing of about 18,000 particles: jamming it takes tens of seconds.
  std::ofstream(dir / "job.json")
      << R"({"test": "uct", "sample": {"diameter": 40, "height": 80, "radius": 1,)"
      << R"( "packing": "random", "seed": 7}, "material": {"kr": 8000}, "bond": {"fr0": 64, "fs0": 64}})";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    setenv("ROCKCAL_PACKING_CACHE", (dir / "cache").c_str(), 1);
    const int out = open((dir / "stdout").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open((dir / "stderr").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, 1);
    dup2(err, 2);
    execl(ROCKCAL_DEM, ROCKCAL_DEM, "run", (dir / "job.json").c_str(), "--out",
          (dir / "out").c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  kill(pid, SIGTERM);
  const auto t0 = std::chrono::steady_clock::now();
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() - t0 > std::chrono::seconds(10)) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      ADD_FAILURE() << "rockcal-dem ignored SIGTERM for 10 s";
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 3) << "status " << status;
  EXPECT_LT(seconds, 1.0);
  std::ifstream err(dir / "stderr");
  const std::string text((std::istreambuf_iterator<char>(err)), {});
  EXPECT_NE(text.find("stopped on request (SIGTERM or SIGINT) while setting up the run"),
            std::string::npos)
      << text;
  EXPECT_FALSE(fs::exists(dir / "out" / "result.json"));
  EXPECT_TRUE(fs::is_empty(dir / "cache")) << "a packing cut short must not be cached";
  fs::remove_all(dir);
}
