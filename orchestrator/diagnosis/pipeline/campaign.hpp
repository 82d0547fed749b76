// A campaign of kind "diagnosis": the lab dataset, the model template, the candidate effects, and
// how finely to look (bounds, grid, budget, confirmation, bootstrap).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/diagnosis/analysis/budget.hpp"
#include "orchestrator/diagnosis/analysis/candidate.hpp"
#include "orchestrator/diagnosis/analysis/observations.hpp"
#include "orchestrator/diagnosis/analysis/verdict.hpp"
#include "orchestrator/diagnosis/dataset/dataset.hpp"

namespace rockcal::diagnosis {

// Where the response surfaces' runs lie. "global": a grid of ln F_r0 and ln F_s0 spread evenly
// over the bounds (ends included), and of s over [0, 1], for every effect. "local"
// (local_design.hpp): the grid for the base model only, a star of half-width `step` (unit cube)
// around its fit, and each effect's s levels at that fit. Three per axis is the least a quadratic
// needs.
enum class Design { global, local };

struct GridSpec {
  Design design = Design::global;
  int fr0 = 4;
  int fs0 = 4;
  int s = 3;
  double step = 0.1;  // local design: a tenth of the box, x1.32 in a strength on the default bounds
};

struct DiagnosisCampaign {
  std::string name;
  nlohmann::json job_template;        // the "job" block: no test, bond or effects
  std::uint64_t sample_seed = 1;      // the template's packing seed
  Dataset dataset;                    // as given
  std::vector<Target> targets;        // the dataset in model units, in dataset order
  std::vector<Candidate> candidates;  // effects only, in request order (the base is implied)
  calibration::Range fr0_n{16, 256};
  calibration::Range fs0_n{16, 256};
  GridSpec grid;
  bool screen = true;     // each effect run once at s = 1 first; those that move nothing dropped
  bool next_test = true;  // after the verdict: the lab test that would tell the leading apart
  BudgetSpec budget;
  int confirm = 2;                // top candidates confirmed by real runs (besides the base)
  int refine = 2;                 // re-fits of each confirmed candidate on run-corrected surfaces
  int bootstrap = 200;            // replicates of the lab and numerical noise for the confidence
  std::uint64_t random_seed = 1;  // the bootstrap's draws
  DecisionRule decision;          // when a gap is one, and the evidence that names an effect
};

// Parses and validates the whole request: the dataset (through the dataset parser), the template
// (through the engine's validation, for every test the dataset needs, with every candidate effect
// switched on at its strong end), the effect names against the registry. Throws
// orch::RequestError naming the first offending field ("dataset.observations[2].value",
// "effects[1]", "grid.s").
DiagnosisCampaign parse_diagnosis_campaign(const nlohmann::json& request);

// Effects are judged on held-out observations only (a better calibration fit proves nothing):
// without any, the effects are screened and each given the lab test that would show it (the next
// test), but not designed, confirmed or ranked.
bool judges_effects(const DiagnosisCampaign& c);

// Every effect the engine registers, in registration order, as candidates; a parameter's neutral
// value may depend on the job (post_break_friction: its contact.friction), hence `model`.
std::vector<Candidate> registry_candidates(const JobSpec& model);

}  // namespace rockcal::diagnosis
