#include "orchestrator/diagnosis/analysis/budget.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "orchestrator/diagnosis/analysis/gap.hpp"

namespace rockcal::diagnosis {

std::vector<ErrorTerm> error_terms(Origin origin) {
  const bool model_made = origin == Origin::same_resolution_model;
  return {
      {"seed", true,
       "the data's specimen is another draw of the packing and of any seeded effect than the "
       "model's run"},
      {"speed", origin == Origin::lab,
       origin == Origin::lab
           ? "the lab loads quasi-statically, the model at a finite platen speed"
           : "the data were made by a model at the same platen speed: they share its rate error"},
      {"resolution", !model_made,
       model_made ? "the data were made at the model's own resolution: they share its lattice cut"
                  : "the data come from a finer specimen than the model's (a lab's grains or a "
                    "finer model), so the model's resolution error is between them; only the "
                    "part of a refinement's change that re-fitting the strengths to the "
                    "calibration observations leaves is charged (the rest is a bias the "
                    "calibration absorbs)"}};
}

std::vector<BudgetVariant> budget_variants(const BudgetSpec& spec, std::uint64_t template_seed,
                                           Origin origin) {
  auto applies = [terms = error_terms(origin)](const std::string& kind) {
    for (const ErrorTerm& t : terms)
      if (t.kind == kind) return t.applies;
    return true;
  };
  std::vector<BudgetVariant> out;
  for (std::uint64_t seed : spec.seeds) {
    out.push_back({"seed " + std::to_string(seed), {seed, 1.0, 1.0}, "seed"});
  }
  auto factor = [](double x) {
    std::string s = std::to_string(x);
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') s.pop_back();
    return s;
  };
  if (applies("speed")) {
    out.push_back(
        {"speed x" + factor(spec.speed_factor), {template_seed, spec.speed_factor, 1.0}, "speed"});
  }
  if (!applies("resolution")) return out;
  for (double r : spec.resolutions) {
    out.push_back({"resolution x" + factor(r), {template_seed, 1.0, r}, "resolution"});
  }
  return out;
}

std::size_t budget_runs_per_point(const BudgetSpec& spec, Origin origin) {
  return 1 + budget_variants(spec, 0, origin).size();
}

std::vector<std::vector<double>> budget_offsets(int points) {
  const double d = kBudgetStep;
  const std::vector<std::vector<double>> all{{0, 0}, {d, 0},   {-d, 0}, {0, d}, {0, -d},
                                             {d, d}, {-d, -d}, {d, -d}, {-d, d}};
  return {all.begin(), all.begin() + std::clamp<std::size_t>(points, 1, all.size())};
}

std::vector<std::vector<double>> budget_points(const std::vector<double>& z, int points) {
  std::vector<std::vector<double>> out;
  for (const std::vector<double>& offset : budget_offsets(points)) {
    std::vector<double> at = z;
    for (std::size_t d = 0; d < at.size(); ++d) at[d] = std::clamp(at[d] + offset[d], 0.0, 1.0);
    if (std::find(out.begin(), out.end(), at) == out.end()) out.push_back(std::move(at));
  }
  return out;
}

double refit_weight(const Target& target) {
  const double scale = std::max(noise_scale(target, 0.0), kMinNoiseScale);
  return 1.0 / (scale * scale);
}

StrengthResponse strength_response(const SurfaceSet& base, const std::vector<Target>& targets,
                                   const std::vector<std::vector<double>>& points) {
  StrengthResponse r;
  for (const Target& t : targets)
    r.weight.push_back(t.role == Role::calibration ? refit_weight(t) : 0.0);
  for (const std::vector<double>& at : points) {
    const std::vector<std::vector<double>> g = surface_gradients(base, at);
    std::vector<std::array<double, 2>> jacobian(targets.size());
    for (std::size_t i = 0; i < jacobian.size(); ++i) jacobian[i] = {g[i][0], g[i][1]};
    r.jacobian.push_back(std::move(jacobian));
  }
  return r;
}

namespace {

bool usable(const std::vector<double>& change, const std::vector<std::array<double, 2>>& jacobian,
            std::size_t i) {
  return std::isfinite(change[i]) && std::isfinite(jacobian[i][0]) && std::isfinite(jacobian[i][1]);
}

}  // namespace

std::array<double, 2> refit_shift(const std::vector<double>& change,
                                  const std::vector<std::array<double, 2>>& jacobian,
                                  const std::vector<double>& weight) {
  // Normal equations: [p q; q r] dz = b.
  double p = 0, q = 0, r = 0, b0 = 0, b1 = 0;
  for (std::size_t i = 0; i < change.size(); ++i) {
    if (!(weight[i] > 0) || !usable(change, jacobian, i)) continue;
    const auto& j = jacobian[i];
    p += weight[i] * j[0] * j[0];
    q += weight[i] * j[0] * j[1];
    r += weight[i] * j[1] * j[1];
    b0 += weight[i] * change[i] * j[0];
    b1 += weight[i] * change[i] * j[1];
  }
  const double det = p * r - q * q, trace = p + r;
  if (trace > 0 && det > 1e-9 * trace * trace) {
    return {(r * b0 - q * b1) / det, (p * b1 - q * b0) / det};
  }
  if (!(trace > 0)) return {0.0, 0.0};
  // One calibration direction (e.g. a single calibration condition): the minimum-norm re-fit
  // along it, the matrix's one non-zero eigenvector.
  double v0 = p >= r ? p : q, v1 = p >= r ? q : r;
  const double norm = std::hypot(v0, v1);
  v0 /= norm;
  v1 /= norm;
  const double along = (v0 * b0 + v1 * b1) / trace;
  return {along * v0, along * v1};
}

std::vector<double> change_after_refit(const std::vector<double>& change,
                                       const std::vector<std::array<double, 2>>& jacobian,
                                       const std::vector<double>& weight) {
  const std::size_t n = change.size();
  const auto [dz0, dz1] = refit_shift(change, jacobian, weight);
  std::vector<double> out(n, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < n; ++i) {
    if (usable(change, jacobian, i))
      out[i] = change[i] - jacobian[i][0] * dz0 - jacobian[i][1] * dz1;
  }
  return out;
}

Budget numerical_budget(std::vector<BudgetVariant> variants,
                        const std::vector<RunOutcome>& references,
                        const std::vector<std::vector<RunOutcome>>& outcomes,
                        const StrengthResponse* response) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = references.empty() ? 0 : references.front().values.size();
  Budget b;
  b.variants = std::move(variants);
  b.points = int(references.size());
  b.per_target.assign(n, 0.0);
  b.measured.assign(n, false);
  for (std::size_t v = 0; v < b.variants.size(); ++v) {
    const bool refit = response && b.variants[v].kind == "resolution";
    std::vector<double> sum(n, 0.0);
    std::vector<int> count(n, 0);
    for (std::size_t p = 0; p < references.size(); ++p) {
      std::vector<double> c(n, nan);
      for (std::size_t i = 0; i < n; ++i) {
        const auto& ref = references[p].values[i];
        const auto& var = outcomes[p][v].values[i];
        if (ref && var) c[i] = std::log(*var / *ref);
      }
      if (refit) c = change_after_refit(c, response->jacobian[p], response->weight);
      for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(c[i])) continue;
        sum[i] += c[i] * c[i];
        ++count[i];
      }
    }
    std::vector<double> change(n, nan);
    for (std::size_t i = 0; i < n; ++i) {
      if (count[i] == 0) continue;
      change[i] = std::sqrt(sum[i] / count[i]);
      b.measured[i] = true;
    }
    b.change.push_back(std::move(change));
    b.refitted.push_back(refit);
  }
  std::set<std::string> kinds;
  for (const BudgetVariant& v : b.variants) kinds.insert(v.kind);
  for (const std::string& kind : kinds) {
    for (std::size_t i = 0; i < n; ++i) {
      double sum = 0.0;
      int count = 0;
      for (std::size_t v = 0; v < b.variants.size(); ++v) {
        if (b.variants[v].kind != kind || !std::isfinite(b.change[v][i])) continue;
        sum += b.change[v][i] * b.change[v][i];
        ++count;
      }
      if (count > 0) b.per_target[i] = std::max(b.per_target[i], std::sqrt(sum / count));
    }
  }
  double largest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (b.measured[i]) largest = std::max(largest, b.per_target[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!b.measured[i]) b.per_target[i] = largest;
  }
  return b;
}

}  // namespace rockcal::diagnosis
