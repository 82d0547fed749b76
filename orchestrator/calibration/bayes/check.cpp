#include "orchestrator/calibration/bayes/check.hpp"

#include <cmath>

namespace rockcal::calibration {
namespace {

// The two-sided 99% standard normal quantile.
constexpr double kZ99 = 2.5758293035489;

}  // namespace

std::optional<CheckAgreement> check_agreement(const PredictedLoad& predicted,
                                              const orch::Ensemble& check) {
  double sum = 0.0;
  int n = 0;
  for (const orch::Realisation& r : check.realisations) {
    if (!r.peak_load_n || *r.peak_load_n <= 0.0) continue;
    sum += std::log(*r.peak_load_n);
    ++n;
  }
  if (n == 0 || predicted.mean_n <= 0.0) return std::nullopt;
  CheckAgreement a;
  a.n = n;
  a.mean_n = std::exp(sum / n);
  a.predicted_n = predicted.mean_n;
  const double d = sum / n - std::log(predicted.mean_n);
  a.relative_to_prediction = std::expm1(d);
  a.relative_to_target = a.mean_n / predicted.target_n - 1.0;
  a.sd = std::sqrt(predicted.emulator_sd * predicted.emulator_sd +
                   predicted.run_sd * predicted.run_sd / n);
  a.z = a.sd > 0.0 ? d / a.sd : 0.0;
  a.agrees = std::abs(d) <= kZ99 * a.sd;
  return a;
}

}  // namespace rockcal::calibration
