#include "orchestrator/diagnosis/analysis/surface_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <nlopt.hpp>

#include "orchestrator/calibration/nlopt_bridge.hpp"

namespace rockcal::diagnosis {

std::vector<double> predict(const SurfaceSet& surfaces, std::span<const double> z) {
  std::vector<double> out;
  out.reserve(surfaces.per_target.size());
  for (const auto& s : surfaces.per_target) {
    out.push_back(s ? evaluate(*s, z) : std::numeric_limits<double>::quiet_NaN());
  }
  return out;
}

std::vector<std::vector<double>> surface_gradients(const SurfaceSet& surfaces,
                                                   std::span<const double> z) {
  constexpr double h = 0.02;
  std::vector<std::vector<double>> g(surfaces.per_target.size(), std::vector<double>(z.size()));
  for (std::size_t d = 0; d < z.size(); ++d) {
    std::vector<double> lo(z.begin(), z.end()), hi = lo;
    lo[d] = std::max(0.0, z[d] - h);
    hi[d] = std::min(1.0, z[d] + h);
    const std::vector<double> up = predict(surfaces, hi), down = predict(surfaces, lo);
    for (std::size_t i = 0; i < g.size(); ++i) g[i][d] = (up[i] - down[i]) / (hi[d] - lo[d]);
  }
  return g;
}

double misfit(const Objective& objective, const std::vector<double>& ln_sim) {
  double sum = 0.0;
  for (std::size_t i = 0; i < ln_sim.size(); ++i) {
    if (objective.weight[i] > 0 && std::isfinite(ln_sim[i])) {
      const double r = ln_sim[i] - objective.ln_lab[i];
      sum += objective.weight[i] * r * r;
    }
  }
  return sum;
}

namespace {

constexpr int kMaxEvaluations = 400;

struct Run {
  std::vector<double> z;
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> history;
};

Run run_from(const SurfaceSet& surfaces, const Objective& objective, std::vector<double> x,
             std::optional<double> fixed_s) {
  const unsigned free_dims = unsigned(x.size());
  nlopt::opt opt(nlopt::LN_BOBYQA, free_dims);
  opt.set_lower_bounds(std::vector<double>(free_dims, 0.0));
  opt.set_upper_bounds(std::vector<double>(free_dims, 1.0));
  opt.set_maxeval(kMaxEvaluations);
  opt.set_xtol_abs(1e-9);
  opt.set_ftol_abs(1e-15);
  opt.set_initial_step(std::vector<double>(free_dims, 0.1));
  Run run;
  auto full = [&](const std::vector<double>& free) {
    std::vector<double> z = free;
    if (fixed_s) z.push_back(*fixed_s);
    return z;
  };
  calibration::minimise(opt, x, [&](const std::vector<double>& free) {
    const std::vector<double> z = full(free);
    const double f = misfit(objective, predict(surfaces, z));
    if (f < run.best) {
      run.best = f;
      run.z = z;
    }
    run.history.push_back(run.best);
    return f;
  });
  return run;
}

}  // namespace

SurfaceCalibration calibrate_on_surfaces(const SurfaceSet& surfaces, const Objective& objective,
                                         const std::vector<std::vector<double>>& starts,
                                         std::optional<double> fixed_s) {
  SurfaceCalibration out;
  out.misfit = std::numeric_limits<double>::infinity();
  for (const std::vector<double>& start : starts) {
    std::vector<double> x = start;
    x.resize(fixed_s ? surfaces.dims - 1 : surfaces.dims, 0.5);
    Run run = run_from(surfaces, objective, x, fixed_s);
    out.evaluations += int(run.history.size());
    if (run.best < out.misfit) {
      out.misfit = run.best;
      out.z = std::move(run.z);
      out.history = std::move(run.history);
    }
  }
  return out;
}

SurfaceCalibration refit_near(const SurfaceSet& surfaces, Objective objective,
                              const std::vector<double>& z, const std::vector<double>& offset) {
  for (std::size_t i = 0; i < offset.size(); ++i) objective.ln_lab[i] -= offset[i];
  std::vector<std::vector<double>> starts{z};
  for (auto& s : lattice_starts(surfaces.dims, 2)) starts.push_back(std::move(s));
  return calibrate_on_surfaces(surfaces, objective, starts);
}

std::vector<std::vector<double>> lattice_starts(int dims, int per_axis) {
  std::vector<std::vector<double>> out{{}};
  for (int d = 0; d < dims; ++d) {
    std::vector<std::vector<double>> next;
    for (const auto& prefix : out) {
      for (int k = 0; k < per_axis; ++k) {
        auto p = prefix;
        p.push_back((2.0 * k + 1.0) / (2.0 * per_axis));
        next.push_back(std::move(p));
      }
    }
    out = std::move(next);
  }
  return out;
}

}  // namespace rockcal::diagnosis
