#include "orchestrator/diagnosis/analysis/identifiability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "orchestrator/diagnosis/analysis/gap.hpp"

namespace rockcal::diagnosis {

Identifiability identifiability(const SurfaceSet& surfaces, const Objective& objective,
                                const std::vector<Target>& targets,
                                const std::vector<double>& budget, int steps,
                                const std::vector<double>* base) {
  const std::size_t n = targets.size();
  const auto starts = lattice_starts(2, 3);
  std::vector<double> at_zero = base ? *base : std::vector<double>{};
  Identifiability out;
  out.max_change.assign(n, std::numeric_limits<double>::quiet_NaN());
  for (int k = 0; k < steps; ++k) {
    const double s = steps > 1 ? double(k) / double(steps - 1) : 0.0;
    const SurfaceCalibration fit = calibrate_on_surfaces(surfaces, objective, starts, s);
    const std::vector<double> ln_sim = predict(surfaces, fit.z);
    if (k == 0 && !base) {
      at_zero = ln_sim;
      continue;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double change = std::abs(ln_sim[i] - at_zero[i]);
      if (!std::isfinite(change)) continue;
      out.max_change[i] =
          std::isfinite(out.max_change[i]) ? std::max(out.max_change[i], change) : change;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    // Budget and lab uncertainty added, not in quadrature: the effect must clear both.
    if (out.max_change[i] > budget[i] + targets[i].sigma) out.moved.push_back(i);
  }
  out.identifiable = std::any_of(out.moved.begin(), out.moved.end(), [&](std::size_t i) {
    return targets[i].role == Role::calibration;
  });
  return out;
}

std::string identifiability_reason(const Identifiability& id, const std::vector<Target>& targets) {
  if (id.moved.empty()) {
    return "moves no observation beyond its budget + lab uncertainty once the strengths are "
           "re-fitted: the strengths absorb it";
  }
  std::string calibration, held_out;
  for (std::size_t i : id.moved) {
    std::string& list = targets[i].role == Role::calibration ? calibration : held_out;
    list += (list.empty() ? "" : ", ") + targets[i].id;
  }
  if (calibration.empty()) {
    return "moves only held-out observations (" + held_out +
           "): the calibration observations cannot fix its parameter, so what it closes at its "
           "fitted value is a choice, not a prediction";
  }
  return "moves calibration observations (" + calibration + "), which fix its parameter" +
         (held_out.empty() ? std::string(", and no held-out one")
                           : ", and held-out ones (" + held_out + ")");
}

}  // namespace rockcal::diagnosis
