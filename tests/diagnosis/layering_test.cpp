// Focus: the diagnosis's layers. The analysis (surfaces, budget, identifiability, gap, verdict,
// bootstrap, ratio) works on observations and run outcomes; it must never reach the request
// (campaign.hpp), the pipeline that runs it (driver, grid, the campaign kind) or the report, so
// that a numerical routine can be tested, reused and reasoned about without them. Follows the
// quoted includes of every analysis file, transitively.
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

}  // namespace

TEST(DiagnosisLayering, TheAnalysisNeverIncludesTheRequestThePipelineOrTheReport) {
  const std::string dir = "orchestrator/diagnosis/";
  const char* analysis[] = {"bootstrap",       "budget", "candidate_result", "gap",
                            "identifiability", "ratio",  "surface",          "surface_fit",
                            "trust_region",    "verdict"};
  const char* forbidden[] = {"campaign.hpp", "diagnosis_kind.hpp", "driver.hpp", "grid.hpp",
                             "jobs.hpp",     "pool_evaluator.hpp", "report.hpp"};
  int files = 0;
  for (const char* name : analysis) {
    for (const char* ext : {".hpp", ".cpp"}) {
      const std::string file = dir + name + ext;
      if (!fs::exists(kRoot / file)) continue;
      ++files;
      std::map<std::string, std::string> seen;
      reach(file, file, seen);
      for (const char* f : forbidden) {
        const auto it = seen.find(dir + f);
        EXPECT_TRUE(it == seen.end()) << it->second;
      }
    }
  }
  EXPECT_GE(files, 19);  // every analysis file was read (candidate_result has no .cpp)
}
