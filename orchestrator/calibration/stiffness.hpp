// The stiffness stage: the bond stiffnesses that give the specimen the target E and nu, found
// before the strength search, which then runs at them.
//
// Eq. 3 gives K_r and K_s/K_r from E and nu exactly for an aligned FCC lattice only; a random
// packing or bonds beyond touching neighbours make the specimen 2-4x stiffer or softer. In a linear
// bonded network (contacts and platens take the bonds' K_r and K_s) the displacements under a given
// strain depend only on stiffness ratios, so nu depends on K_s/K_r (and the packing) alone and E is
// proportional to K_r at a fixed K_s/K_r (tests/engine/stiffness_scale_test.cpp checks both on the
// engine). Hence: a 1-D NLopt search over ln(K_s/K_r) (through eq. 3's nu, K_s/K_r = (1 - 3 nu) /
// (1 + nu), which sets the bending and twisting ratios too) on elastic tests for the target nu,
// from the target itself (eq. 3 as the start); when the template bonds beyond touching
// neighbours and no K_s/K_r reaches a target nu above the packing's, a 1-D NLopt search over the
// long bonds' stiffness exponent at the best K_s/K_r, for the stiffest long bonds that put nu
// within the tolerance (they carry the UCS/BTS ratio the range is there for); then K_r times
// E_target / E_measured, one
// multiplication; then one elastic run that confirms both. E is the elastic test's: axial stress
// over axial strain in the specimen's interior, as a lab's strain gauges measure it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/evaluator.hpp"

namespace rockcal::calibration {

// Eq. 3's nu that the search may take: K_s/K_r from 5 down to 0.077.
inline constexpr double kStiffnessNuLo = -0.5;
inline constexpr double kStiffnessNuHi = 0.3;
inline constexpr int kStiffnessNuRuns = 10;          // elastic runs the nu search may take
inline constexpr double kLongBondExponentMax = 8.0;  // the effect's documented range
inline constexpr int kLongBondRuns = 8;  // elastic runs the search over the exponent may take
inline constexpr double kStiffnessNuTolerance = 0.03;  // |nu - target| that meets the target
inline constexpr double kStiffnessETolerance = 0.05;   // |E / target - 1| that meets the target
// Packings each elastic run measures when the template's seed makes another specimen (a random
// packing's nu scatters by about 0.1 between packings at D/R 16): the run's E and nu are means.
inline constexpr int kStiffnessPackings = 4;

// The job template's stiffness as the stage changes it: the material field it states ("kr" or
// "youngs_modulus", eq. 3's input) times a factor, and eq. 3's nu.
struct StiffnessSetting {
  double scale = 1.0;  // of the template's stiffness field
  double nu = 0.2;     // eq. 3's nu
  // The interaction range's stiffness_exponent n: bonds beyond touching get their stiffnesses
  // times ((R_i + R_j) / L)^n. 0 (none) unless the template bonds beyond touching neighbours and
  // no K_s/K_r reaches the target nu there: those bonds, as stiff as the touching ones, hold the
  // lattice's nu down (docs/reach.md, "Softer long bonds").
  double long_bond_exponent = 0.0;
};

// One elastic run of the stage.
struct StiffnessRun {
  // "nu" (the search), "long_bonds" (the exponent's search), "start" (E alone: the
  // template's), "confirm"
  std::string phase;
  StiffnessSetting setting;
  double kr_n_m = 0.0;  // the normal bond stiffness it ran (at the sample's mean radius)
  // Means over the packings that measured both (model units), and their standard deviations.
  std::optional<double> youngs_modulus_pa;
  std::optional<double> poisson_ratio;
  std::optional<double> youngs_modulus_sd;
  std::optional<double> poisson_ratio_sd;
  int packings = 0;                   // that measured both
  std::vector<std::int64_t> job_ids;  // one per packing (0 outside the service)
  std::string error;                  // the first failed packing's
};

struct StiffnessResult {
  StiffnessSetting setting;  // what the strength search ran at
  double kr_n_m = 0.0;
  double ks_over_kr = 0.0;
  std::optional<double> target_youngs_modulus_pa;  // model units
  std::optional<double> target_poisson_ratio;
  std::optional<double> youngs_modulus_pa;  // the confirming run's means
  std::optional<double> poisson_ratio;
  std::optional<double> poisson_ratio_sd;  // between its packings
  int packings = 0;
  // The nu the search's runs measured at their extremes of K_s/K_r: the packing's reach so far.
  std::optional<double> nu_reached_lo;
  std::optional<double> nu_reached_hi;
  std::vector<StiffnessRun> runs;
  std::string why;  // a sentence from the fields above
};

// Whether the confirming run met every target the request gave (E within 5%, nu within 0.03).
bool stiffness_met(const StiffnessResult& result);

// The patch of "job" that runs a setting: {"material": {field: template value x scale, "nu"}},
// with {"effects": {"interaction_range": {"stiffness_exponent": n}}} when n > 0 or the template
// has an interaction range (so that a later stage at another range resets it).
nlohmann::json stiffness_patch(const nlohmann::json& job_template, const StiffnessSetting& setting);

// Runs the stage on the campaign's targets.elastic (nothing when it has none) and leaves the
// evaluator's template at the result. Elastic runs are probes at the strongest bonds of the box
// (none breaks at the elastic strain), on the template's seed and, when the seed matters, the
// next kStiffnessPackings - 1. Throws what the evaluator throws.
std::optional<StiffnessResult> calibrate_stiffness(const CalibrationCampaign& campaign,
                                                   Evaluator& evaluator);

// The report's "stiffness" block: model units, with a "lab" block when the targets are lab ones.
nlohmann::json to_json(const StiffnessResult& result, const CalibrationCampaign& campaign);

}  // namespace rockcal::calibration
