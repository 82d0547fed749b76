#include "engine/loadtests/quasi_static_rerun.hpp"

#include <algorithm>

#include "engine/effects/effect.hpp"
#include "engine/loadtests/driver.hpp"
#include "engine/run_cost.hpp"
#include "engine/spec.hpp"

namespace rockcal {

TestResult run_with_quasi_static_rerun(const JobSpec& spec, const RunHooks& hooks,
                                       CompressionRun run) {
  TestResult first = run(spec, hooks);
  if (!spec.loading.quasi_static_rerun || !first.peak_reached || !first.loading_rate ||
      first.loading_rate->quasi_static() || first.stop_reason == "cancelled")
    return first;
  const LoadingRate& q = *first.loading_rate;
  const double factor =
      std::min(kMaxRerunFactor, kRerunMargin * q.min_transits / std::max(q.peak_transits, 1.0));
  JobSpec slower = spec;
  slower.loading.auto_transits = spec.loading.auto_transits * factor;
  slower.loading.follow_transits = spec.loading.follow_transits * factor;  // 0 stays off
  if (estimated_steps(effective_spec(slower)) > static_cast<double>(kMaxSteps)) return first;
  TestResult second = run(slower, hooks);
  // A slower run that found no peak (stopped at max_steps or max_strain) does not replace a peak.
  if (!second.peak_reached && second.stop_reason != "cancelled") {
    first.wall_seconds += second.wall_seconds;
    return first;
  }
  second.wall_seconds += first.wall_seconds;
  if (second.loading_rate) {
    second.loading_rate->rerun =
        QuasiStaticRerun{q.peak_transits, first.peak_load_n, slower.loading.auto_transits};
  }
  return second;
}

}  // namespace rockcal
