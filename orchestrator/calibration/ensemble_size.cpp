#include "orchestrator/calibration/ensemble_size.hpp"

#include <algorithm>
#include <cmath>

#include "orchestrator/calibration/sentence.hpp"
#include "orchestrator/calibration/start_design.hpp"

namespace rockcal::calibration {
namespace {

std::optional<double> cv_of(const std::optional<orch::Ensemble>& e) {
  if (!e || e->peak_load.n < 2 || !e->peak_load.sd || !e->peak_load.mean || *e->peak_load.mean <= 0)
    return std::nullopt;
  return *e->peak_load.sd / *e->peak_load.mean;
}

std::string percent(const std::optional<double>& cv) {
  return cv ? sentence("%.3g%%", 100 * *cv) : std::string("unmeasured");
}

}  // namespace

int realisations_for(double cv, double tolerance) {
  // Not capped at what a campaign may run: the report says what the scatter calls for.
  const double n = std::ceil(std::pow(2.0 * cv / tolerance, 2));
  return int(std::clamp(n, 1.0, 1e9));
}

ScatterEstimate scatter_estimate(std::optional<double> cv_uct, std::optional<double> cv_btt,
                                 int runs, double tolerance) {
  ScatterEstimate s{cv_uct, cv_btt, runs, std::nullopt};
  if (cv_uct && cv_btt) {
    s.needed = std::max(realisations_for(*cv_uct, tolerance), realisations_for(*cv_btt, tolerance));
  }
  return s;
}

ScatterEstimate scatter_estimate(const std::optional<orch::Ensemble>& uct,
                                 const std::optional<orch::Ensemble>& btt, double tolerance) {
  return scatter_estimate(cv_of(uct), cv_of(btt),
                          std::min(uct ? uct->peak_load.n : 0, btt ? btt->peak_load.n : 0),
                          tolerance);
}

EnsembleSize choose_ensemble_size(const CalibrationCampaign& c, Evaluator& evaluator) {
  EnsembleSize size;
  size.automatic = c.auto_realisations;
  size.realisations = c.realisations;
  if (!c.auto_realisations) return size;
  const EvaluationRequest pilot{start_design(c).front(), c.sample_seed, kPilotRealisations};
  const std::vector<EvaluationOutcome> out = evaluator.evaluate_batch({&pilot, 1});
  if (!out.empty()) size.pilot = scatter_estimate(out[0].uct, out[0].btt, c.tolerance);
  // Without a measured scatter (the pilot failed, or an evaluator that reports no realisations)
  // the cap is the safe side: a too-small ensemble would claim a precision it does not have.
  const int wanted = size.pilot.needed.value_or(c.max_realisations);
  size.realisations = std::min(wanted, c.max_realisations);
  size.capped = wanted > c.max_realisations || !size.pilot.needed;
  return size;
}

void review_ensemble_size(EnsembleSize& size, const EvaluationRecord* best,
                          const std::optional<ScatterEstimate>& scatter, double tolerance) {
  if (best) size.at_best = scatter_estimate(best->uct, best->btt, tolerance);
  if (!size.at_best.needed && scatter) size.at_best = *scatter;
  const ScatterEstimate& basis = size.at_best;
  const double half = 50 * tolerance;
  auto cvs = [](const ScatterEstimate& e) {
    return "peak-load CV UCT " + percent(e.cv_uct) + ", BTT " + percent(e.cv_btt);
  };
  if (size.automatic) {
    size.why = sentence(
                   "%.0f realisations per evaluation, chosen from a pilot of %.0f at the "
                   "first start point (",
                   double(size.realisations), double(kPilotRealisations)) +
               cvs(size.pilot) + ")";
    if (!size.pilot.needed) {
      size.why += "; the pilot measured no scatter, so the cap (max_realisations) was used";
    } else if (size.capped) {
      size.why += sentence("; a standard error of %.3g%% would need %.0f, beyond max_realisations",
                           half, double(*size.pilot.needed));
    }
  } else {
    size.why = sentence("%.0f realisation(s) per evaluation, as the campaign asked",
                        double(size.realisations));
  }
  const char* unseen =
      "one packing per evaluation: its loads carry the cut's error unseen (ask "
      "for \"realisations\": \"auto\")";
  if (basis.needed) {
    size.why += "; at the best point (" + cvs(basis) + ")" +
                sentence(" a standard error of %.3g%% of each load needs %.0f", half,
                         double(*basis.needed));
    if (size.realisations == 1 && basis.runs > 1) {
      size.why += sentence(" (from its re-runs on %.0f packings) - ", double(basis.runs)) + unseen;
    } else if (*basis.needed > size.realisations) {
      size.why +=
          " - more than were run: the tolerance test is widened by the larger standard "
          "error, and the consistent set is wider for it";
    }
  } else if (size.realisations == 1) {
    size.why += std::string("; ") + unseen + ", and no scatter was measured";
  }
}

}  // namespace rockcal::calibration
