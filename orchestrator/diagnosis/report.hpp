// What a diagnosis found: the campaign summary (JSON) and the HTML page of a diagnosis campaign.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "orchestrator/diagnosis/budget.hpp"
#include "orchestrator/diagnosis/campaign.hpp"
#include "orchestrator/diagnosis/candidate.hpp"
#include "orchestrator/diagnosis/evaluator.hpp"
#include "orchestrator/diagnosis/ratio.hpp"
#include "orchestrator/diagnosis/surface_fit.hpp"

namespace rockcal::diagnosis {

struct RmsByRole {
  std::optional<double> calibration;
  std::optional<double> held_out;
};

// Whether the data can see an effect at all: with the bond strengths re-fitted to the calibration
// targets at each s in [0, 1], how far does each observation move from its s = 0 value?
struct Identifiability {
  bool identifiable = false;
  std::vector<double> max_change;  // per target, |ln| (NaN without a surface)
  std::vector<std::size_t> moved;  // targets moved beyond budget + lab uncertainty
};

// One real run of the refinement: where, and its real calibration misfit (infinite when a
// calibration observation had no value).
struct RefineStep {
  ModelPoint point;
  double misfit = 0.0;
};

struct CandidateResult {
  Candidate candidate;
  bool fitted = false;
  std::string error;  // why it could not be fitted
  SurfaceSet surfaces;
  SurfaceCalibration calibration;
  ModelPoint point;                                         // the fitted model
  double value = std::numeric_limits<double>::quiet_NaN();  // the effect parameter at point.s
  std::vector<double> predicted;                            // ln(sim) on the surfaces
  RmsByRole surface_rms;
  std::optional<double> g_surface;
  std::optional<Identifiability> identifiability;  // effects only
  // Whether it fits the calibration observations about as well as the best candidate does (see
  // mark_calibration_fits): one that does not cannot be the explanation, however it predicts.
  bool fits_calibration = true;
  bool confirmed = false;
  std::vector<double> confirmed_ln;  // ln(sim) of the real runs at the fitted point (NaN: failed)
  RmsByRole confirmed_rms;
  std::optional<double> g_confirmed;
  std::vector<std::vector<double>> seed_ln;  // real runs with each budget seed (confirmed only)
  // Confirmed only: real minus surface ln values at the fitted point (0 where either is missing).
  // The surfaces plus this offset pass through the real run; the refinement re-fits on them.
  std::vector<double> surface_offset;
  std::vector<RefineStep> refinement;  // the real runs at successive fits, first = surface fit
  int rank = 0;                        // 1 = best effect; 0 for the base

  std::optional<double> g() const { return confirmed ? g_confirmed : g_surface; }
  const std::vector<double>& ln_sim() const { return confirmed ? confirmed_ln : predicted; }
  RmsByRole rms() const { return confirmed ? confirmed_rms : surface_rms; }
};

// The verdict under one replicate packing seed: base and confirmed candidates re-run at their
// fitted points on that packing.
struct SeedCheck {
  std::uint64_t seed = 0;
  std::string verdict;  // effect name, or "" for no effect needed
  std::map<std::string, double> gap_closure;
  // False when every re-run equals its nominal run: a regular packing with no seeded effect does
  // not depend on the seed, and the check then repeats the verdict instead of testing it.
  bool informative = true;
};

struct Confidence {
  int replicates = 0;                  // bootstrap replicates
  double agreement = 0.0;              // share of them with the nominal verdict
  std::map<std::string, int> winners;  // verdict ("" = none) -> replicates
  std::vector<SeedCheck> seeds;
  int seeds_informative = 0;  // of `seeds`; only these count
  int seeds_agreeing = 0;     // informative seeds that reach the nominal verdict
  std::string level;          // high | medium | low
};

struct Verdict {
  int candidate = -1;  // index into candidates; -1 = no effect needed
  int runner_up = -1;
  std::string reason;
};

struct DiagnosisReport {
  // The budget the residuals are judged against (gap test, calibration-fit rule after the
  // confirmations, seed checks, bootstrap), measured at the base model's confirmed fit (the model
  // whose residuals they are; on a demo twin the budget doubled between the two fits).
  Budget budget;
  ModelPoint budget_point;
  // The first budget, at the base model's fit on lab uncertainties alone: the calibrations'
  // weights. The same as `budget` when the confirmed fit kept the first fit's budget points.
  Budget weight_budget;
  ModelPoint weight_budget_point;
  double combined_calibration = 0.0;
  double combined_held_out = 0.0;
  // The base model's held-out residuals (real runs) in budgets: rms_in_budgets, what the verdict
  // calls a gap above kGapBudgets.
  std::optional<double> held_out_budgets;
  std::vector<CandidateResult> candidates;  // [0] = the base, then the effects in request order
  std::optional<LabRatio> ratio;
  Verdict verdict;
  Confidence confidence;
  int model_points = 0;  // distinct model points run (each = one job per distinct condition)
  int failed_values = 0;
  std::string first_error;              // of the first run that left a value missing
  std::vector<int> base_grid_failures;  // per target: base grid runs without a value
};

inline constexpr double kMinGapClosure = 0.3;  // docs/diagnosis.md: verdict rule

// The campaign summary: model units throughout.
nlohmann::json to_json(const DiagnosisReport& report, const DiagnosisCampaign& campaign);

// A self-contained page (inline SVG, no external assets) of a summary made by to_json.
std::string report_html(const nlohmann::json& summary);

}  // namespace rockcal::diagnosis
