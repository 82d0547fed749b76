// Focus: the inference core's layers (orchestrator/inference/CMakeLists.txt): emulator < posterior
// < design, and none of them reaches the calibration, the diagnosis or the service, so that the
// numerical core can be tested and reused without them. Follows the quoted includes of every file
// of a layer, transitively.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = ROCKCAL_SOURCE_DIR;

void reach(const std::string& file, const std::string& chain,
           std::map<std::string, std::string>& seen) {
  std::ifstream in(kRoot / file);
  static const std::regex include(R"re(^\s*#\s*include\s*"([^"]+)")re");
  std::smatch m;
  for (std::string line; std::getline(in, line);) {
    if (!std::regex_search(line, m, include)) continue;
    const std::string h = m[1];
    if (seen.count(h) || !fs::exists(kRoot / h)) continue;
    seen[h] = chain + " -> " + h;
    reach(h, seen[h], seen);
  }
}

// Chains from a file of orchestrator/inference/`folder` to a project header outside the allowed
// inference folders.
std::vector<std::string> reaches_outside(const std::string& folder,
                                         const std::vector<std::string>& allowed) {
  std::vector<std::string> out;
  int files = 0;
  for (const auto& e : fs::directory_iterator(kRoot / "orchestrator/inference" / folder)) {
    const std::string file =
        "orchestrator/inference/" + folder + "/" + e.path().filename().string();
    ++files;
    std::map<std::string, std::string> seen;
    reach(file, file, seen);
    for (const auto& [header, chain] : seen) {
      bool ok = false;
      for (const std::string& a : allowed)
        ok |= header.rfind("orchestrator/inference/" + a + "/", 0) == 0;
      if (!ok) out.push_back(chain);
    }
  }
  EXPECT_GT(files, 1) << folder;
  return out;
}

using Chains = std::vector<std::string>;

}  // namespace

TEST(InferenceLayering, EachLayerIncludesOnlyTheLayersBelowIt) {
  EXPECT_EQ(reaches_outside("emulator", {"emulator"}), Chains{});
  EXPECT_EQ(reaches_outside("posterior", {"emulator", "posterior"}), Chains{});
  EXPECT_EQ(reaches_outside("design", {"emulator", "posterior", "design"}), Chains{});
}

TEST(InferenceLayering, TheCheckSeesAnInclusionAbove) {
  const Chains found = reaches_outside("design", {"emulator", "design"});
  ASSERT_FALSE(found.empty());
  EXPECT_NE(found.front().find("orchestrator/inference/posterior/"), std::string::npos);
}
