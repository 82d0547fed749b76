// What fitting one candidate (the base model, or the base with one effect) to the calibration
// observations gives: its surfaces and fitted point, its identifiability, the real runs that
// confirmed and refined the fit. The analysis produces these; the report only shows them.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/candidate.hpp"
#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/analysis/evidence.hpp"
#include "orchestrator/diagnosis/analysis/surface_fit.hpp"

namespace rockcal::diagnosis {

struct RmsByRole {
  std::optional<double> calibration;
  std::optional<double> held_out;
};

// Whether the data can see an effect at all: with the bond strengths re-fitted to the calibration
// targets at each s in [0, 1], how far does each observation move from its s = 0 value?
struct Identifiability {
  // Some target in `moved` is a calibration observation, so fitting them fixes the effect's
  // parameter (identifiability.hpp).
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
  // Confirmed effects only: the effect's own mark at its fitted value, the largest
  // |ln(its run / the base model's run at the same strengths)| over the observations, in units of
  // each one's noise (budget + lab uncertainty). At most 1: the effect changes nothing there (an
  // interaction range below the packing's next neighbours, say), so its evidence is the
  // strengths' re-fit, not the effect, and it is never the verdict (inert_at_fit).
  std::optional<double> mark_at_fit;
  // Confirmed only: real minus surface ln values at the fitted point (0 where either is missing).
  // The surfaces plus this offset pass through the real run; the refinement re-fits on them.
  std::vector<double> surface_offset;
  std::vector<RefineStep> refinement;  // the real runs at successive fits, first = surface fit
  // The held-out log predictive density of its real runs if confirmed, else of its surfaces with
  // their emulator variance (evidence.hpp); and, for an effect, its lpd minus the base model's.
  std::optional<HeldOutDensity> density;
  std::optional<double> evidence;  // nats
  int rank = 0;                    // 1 = best effect; 0 for the base

  bool inert_at_fit() const { return mark_at_fit && *mark_at_fit <= 1.0; }
  std::optional<double> g() const { return confirmed ? g_confirmed : g_surface; }
  const std::vector<double>& ln_sim() const { return confirmed ? confirmed_ln : predicted; }
  RmsByRole rms() const { return confirmed ? confirmed_rms : surface_rms; }
};

}  // namespace rockcal::diagnosis
