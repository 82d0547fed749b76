#include "orchestrator/diagnosis/pipeline/grid.hpp"

#include <algorithm>
#include <cmath>

#include "orchestrator/diagnosis/analysis/bootstrap.hpp"
#include "orchestrator/diagnosis/analysis/gap.hpp"
#include "orchestrator/diagnosis/analysis/screen.hpp"

namespace rockcal::diagnosis {

std::vector<double> grid_axis(int n) {
  std::vector<double> out;
  for (int k = 0; k < n; ++k) out.push_back(n == 1 ? 0.5 : double(k) / double(n - 1));
  return out;
}

ModelPoint model_point(const DiagnosisCampaign& c, const Candidate& candidate,
                       std::span<const double> z) {
  auto along = [](const calibration::Range& r, double u) {
    return std::exp(std::log(r.lo) + u * (std::log(r.hi) - std::log(r.lo)));
  };
  ModelPoint p{along(c.fr0_n, z[0]), along(c.fs0_n, z[1]), candidate.effect, 0.0};
  if (!candidate.is_base() && z.size() > 2) p.s = candidate.s_at(z[2]);
  return p;
}

int grid_levels(const Candidate& candidate, int s_values) {
  return candidate.shares_base_grid() ? s_values - 1 : s_values;
}

int base_grid_points(const DiagnosisCampaign& c) {
  // The local design adds a star at the base fit, and at most kStarMoves more (each shares at
  // least its centre's arm with the last): an upper bound, as every plan is.
  return c.grid.fr0 * c.grid.fs0 + (c.grid.design == Design::local ? 5 + 4 * kStarMoves : 0);
}

int effect_grid_points(const DiagnosisCampaign& c, const Candidate& k) {
  if (c.grid.design == Design::local) {
    // Its s levels at the fit and two arms at s = 1, or a star at each level and a corner for an
    // effect that jumps at neutral.
    return k.shares_base_grid() ? c.grid.s - 1 + 2 : 5 * c.grid.s + 1;
  }
  return c.grid.fr0 * c.grid.fs0 * grid_levels(k, c.grid.s);
}

int grid_points(const DiagnosisCampaign& c) {
  const int places = c.grid.design == Design::local ? 1 + kEffectMoves : 1;
  int points = base_grid_points(c);
  for (const Candidate& k : c.candidates) points += places * effect_grid_points(c, k);
  return points;
}

int screen_model_points(const DiagnosisCampaign& c) {
  // At the first point, and at most as many again and the base's run at the second.
  return c.screen && !c.candidates.empty() ? 1 + 2 * kScreenRunsPerEffect * int(c.candidates.size())
                                           : 0;
}

Samples run_base_grid(const DiagnosisCampaign& c, Evaluator& evaluator) {
  const Candidate base;
  const Numerics numerics{c.sample_seed, 1.0, 1.0};
  Samples samples;
  std::vector<RunRequest> requests;
  for (double x : grid_axis(c.grid.fr0)) {
    for (double y : grid_axis(c.grid.fs0)) {
      samples.z.push_back({x, y});
      requests.push_back({model_point(c, base, std::vector<double>{x, y}), numerics});
    }
  }
  samples.outcomes = evaluator.run_batch(requests);
  return samples;
}

void run_effect_grids(const DiagnosisCampaign& c, Evaluator& evaluator,
                      std::vector<Samples>& samples) {
  const Numerics numerics{c.sample_seed, 1.0, 1.0};
  samples.resize(1 + c.candidates.size());
  std::vector<RunRequest> requests;
  std::vector<std::size_t> owner;  // which candidate's samples each request feeds
  for (std::size_t k = 0; k < c.candidates.size(); ++k) {
    const Candidate& candidate = c.candidates[k];
    for (double s : grid_axis(c.grid.s)) {
      if (candidate.shares_base_grid() && s <= kEffectOffBelow) continue;  // the base grid
      for (double x : grid_axis(c.grid.fr0)) {
        for (double y : grid_axis(c.grid.fs0)) {
          samples[k + 1].z.push_back({x, y, s});
          requests.push_back(
              {model_point(c, c.candidates[k], std::vector<double>{x, y, s}), numerics});
          owner.push_back(k + 1);
        }
      }
    }
  }
  const std::vector<RunOutcome> outcomes = evaluator.run_batch(requests);
  for (std::size_t r = 0; r < outcomes.size(); ++r)
    samples[owner[r]].outcomes.push_back(outcomes[r]);
  share_base_slice(samples, c);
}

void append_base_slice(Samples& effect, const Samples& base) {
  for (std::size_t r = 0; r < base.z.size(); ++r) {
    std::vector<double> z = base.z[r];
    z.push_back(0.0);
    effect.z.push_back(std::move(z));
    effect.outcomes.push_back(base.outcomes[r]);
  }
}

void share_base_slice(std::vector<Samples>& samples, const DiagnosisCampaign& c) {
  for (std::size_t k = 1; k < samples.size(); ++k) {
    if (c.candidates[k - 1].shares_base_grid()) append_base_slice(samples[k], samples[0]);
  }
}

SurfaceSet fit_surfaces(const Samples& samples, int dims, std::size_t targets) {
  SurfaceSet set;
  set.dims = dims;
  for (std::size_t i = 0; i < targets; ++i) {
    std::vector<std::vector<double>> z;
    std::vector<double> y;
    for (std::size_t r = 0; r < samples.outcomes.size(); ++r) {
      const auto& v = samples.outcomes[r].values[i];
      if (!v) continue;
      z.push_back(samples.z[r]);
      y.push_back(std::log(*v));
    }
    set.per_target.push_back(fit_surface(z, y));
  }
  return set;
}

std::optional<SurfaceCalibration> fit_on_lab(const DiagnosisCampaign& c,
                                             const SurfaceSet& surfaces) {
  const Objective objective = calibration_objective(
      c.targets, std::vector<double>(c.targets.size(), 0.0), surfaces, ln_lab(c.targets));
  if (std::none_of(objective.weight.begin(), objective.weight.end(),
                   [](double w) { return w > 0; })) {
    return std::nullopt;
  }
  return calibrate_on_surfaces(surfaces, objective, lattice_starts(surfaces.dims, 3));
}

}  // namespace rockcal::diagnosis
