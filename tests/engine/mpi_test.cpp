// The decomposed engine agrees with the serial one: same specimen, same peak, same damage at peak.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {

nlohmann::json run_on(int ranks, const fs::path& out) {
  fs::remove_all(out);
  // Root needs Open MPI's consent; more ranks than free cores need oversubscription.
  const std::string cmd =
      std::string(
          "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe -np ") +
      std::to_string(ranks) + " " + ROCKCAL_DEM + " run " + ROCKCAL_EXAMPLES +
      "/uct_small.json --out " + out.string() + " > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd;
  std::ifstream in(out / "result.json");
  if (!in) return nlohmann::json::object();
  return nlohmann::json::parse(in);
}

}  // namespace

TEST(Mpi, TwoRanksAgreeWithOne) {
  const fs::path base = fs::temp_directory_path() / ("rockcal_mpi_" + std::to_string(::getpid()));
  const auto one = run_on(1, base / "np1");
  const auto two = run_on(2, base / "np2");
  ASSERT_TRUE(one.contains("peak_load") && two.contains("peak_load"));
  EXPECT_EQ(two["ranks"], 2);
  EXPECT_EQ(one["particles"], two["particles"]);
  EXPECT_EQ(one["bonds"], two["bonds"]);
  const double p1 = one["peak_load"], p2 = two["peak_load"];
  EXPECT_NEAR(p2 / p1, 1.0, 0.005);
  const double b1 = one["broken_bonds_at_peak"], b2 = two["broken_bonds_at_peak"];
  EXPECT_GT(b1, 0);
  EXPECT_NEAR(b2 / b1, 1.0, 0.01);
  EXPECT_EQ(one["stop_reason"], "post_peak");
  EXPECT_EQ(two["stop_reason"], "post_peak");
  fs::remove_all(base);
}
