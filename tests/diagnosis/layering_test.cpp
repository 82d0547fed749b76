// Focus: the diagnosis's layers (orchestrator/diagnosis/CMakeLists.txt). Each folder includes only
// the folders below it: dataset < twin; dataset < analysis < pipeline < report < the campaign kind.
// And below every domain the one job runner: calibration and diagnosis reach the service's pool
// only through their campaign kinds.
// Above all the analysis (surfaces, budget, identifiability, gap, verdict) works on observations
// and run outcomes and must never reach the request, the pipeline that runs it or the report, so
// that a numerical routine can be tested, reused and reasoned about without them. Follows the
// quoted includes of every file of a layer, transitively.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = ROCKCAL_SOURCE_DIR;

std::vector<std::string> quoted_includes(const fs::path& file) {
  std::ifstream in(kRoot / file);
  EXPECT_TRUE(in) << file;
  static const std::regex include(R"re(^\s*#\s*include\s*"([^"]+)")re");
  std::vector<std::string> out;
  std::smatch m;
  for (std::string line; std::getline(in, line);) {
    if (std::regex_search(line, m, include)) out.push_back(m[1]);
  }
  return out;
}

// Every project header `file` reaches, with the chain that reached it.
void reach(const std::string& file, const std::string& chain,
           std::map<std::string, std::string>& seen) {
  for (const std::string& h : quoted_includes(file)) {
    if (seen.count(h) || !fs::exists(kRoot / h)) continue;
    seen[h] = chain + " -> " + h;
    reach(h, seen[h], seen);
  }
}

// The files of orchestrator/diagnosis/`folder`.
std::vector<std::string> layer(const std::string& folder) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(kRoot / "orchestrator/diagnosis" / folder)) {
    const std::string ext = e.path().extension().string();
    if (ext == ".hpp" || ext == ".cpp") {
      out.push_back("orchestrator/diagnosis/" + folder + "/" + e.path().filename().string());
    }
  }
  return out;
}

// Every chain from a file of `folder` to a diagnosis file outside `allowed` (folders, or
// "diagnosis_kind" for the campaign kind at the top).
std::vector<std::string> reaches_above(const std::string& folder,
                                       const std::vector<std::string>& allowed) {
  std::vector<std::string> out;
  for (const std::string& file : layer(folder)) {
    std::map<std::string, std::string> seen;
    reach(file, file, seen);
    for (const auto& [header, chain] : seen) {
      const std::string prefix = "orchestrator/diagnosis/";
      if (header.rfind(prefix, 0) != 0) continue;
      const std::string rest = header.substr(prefix.size());
      const std::string top = rest.substr(0, rest.find_first_of("/."));
      if (std::find(allowed.begin(), allowed.end(), top) == allowed.end()) out.push_back(chain);
    }
  }
  return out;
}

using Chains = std::vector<std::string>;

// Every chain from a file under `folder` (recursively), other than a campaign kind (*_kind.*), to
// the service or its pool.
std::vector<std::string> reaches_the_pool(const std::string& folder) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(kRoot / folder)) {
    const std::string ext = e.path().extension().string();
    const std::string name = e.path().stem().string();
    if ((ext != ".hpp" && ext != ".cpp") || name.ends_with("_kind")) continue;
    const std::string file = fs::relative(e.path(), kRoot).string();
    std::map<std::string, std::string> seen;
    reach(file, file, seen);
    for (const char* pool : {"orchestrator/job_service.hpp", "orchestrator/pool_runner.hpp"}) {
      if (seen.count(pool)) out.push_back(seen[pool]);
    }
  }
  return out;
}

}  // namespace

TEST(DiagnosisLayering, TheAnalysisNeverIncludesTheRequestThePipelineOrTheReport) {
  EXPECT_GE(layer("analysis").size(), 23u);  // every analysis file is read
  EXPECT_EQ(reaches_above("analysis", {"dataset", "analysis"}), Chains{});
}

TEST(DiagnosisLayering, EachLayerIncludesOnlyTheLayersBelowIt) {
  EXPECT_EQ(reaches_above("dataset", {"dataset"}), Chains{});
  EXPECT_EQ(reaches_above("twin", {"dataset", "twin"}), Chains{});
  EXPECT_EQ(reaches_above("pipeline", {"dataset", "analysis", "pipeline"}), Chains{});
  EXPECT_EQ(reaches_above("report", {"dataset", "analysis", "pipeline", "report"}), Chains{});
}

TEST(DiagnosisLayering, TheSurfacesAreTheInferenceCoresEmulators) {
  // One emulator for calibration and diagnosis: the analysis's surfaces are the inference core's
  // Gaussian process, and the core reaches nothing of the diagnosis.
  std::map<std::string, std::string> seen;
  reach("orchestrator/diagnosis/analysis/surface.hpp", "surface.hpp", seen);
  EXPECT_TRUE(seen.count("orchestrator/inference/emulator/gp.hpp"));
  std::map<std::string, std::string> core;
  reach("orchestrator/inference/emulator/gp.cpp", "gp.cpp", core);
  for (const auto& [header, chain] : core)
    EXPECT_EQ(header.rfind("orchestrator/diagnosis/", 0), std::string::npos) << chain;
}

TEST(DiagnosisLayering, TheCheckSeesAnInclusionAbove) {
  // The test of the test: the report reaches the pipeline's request, which the analysis may not.
  const Chains found = reaches_above("report", {"dataset", "analysis", "report"});
  ASSERT_FALSE(found.empty());
  EXPECT_NE(found.front().find("orchestrator/diagnosis/pipeline/"), std::string::npos);
}

TEST(RunnerLayering, TheDomainsRunJobsOnlyThroughTheOneRunner) {
  // Calibration and diagnosis (twins included) see the engine through orchestrator/job_runner.hpp;
  // only their campaign kinds put the service's pool behind it.
  EXPECT_EQ(reaches_the_pool("orchestrator/calibration"), Chains{});
  EXPECT_EQ(reaches_the_pool("orchestrator/diagnosis"), Chains{});
}

TEST(RunnerLayering, TheCheckSeesTheKindsReachThePool) {
  std::map<std::string, std::string> seen;
  reach("orchestrator/calibration/calibration_kind.cpp", "calibration_kind.cpp", seen);
  EXPECT_TRUE(seen.count("orchestrator/pool_runner.hpp"));
}
