#include "orchestrator/diagnosis/pipeline/local_design.hpp"

#include <algorithm>
#include <cmath>

namespace rockcal::diagnosis {

std::vector<double> lattice_point(std::span<const double> z, double h) {
  // Integer multiples of h, so that two fits near one node give the same doubles (and the same job
  // identities); the last node is the largest k h whose arm (k + 1) h still lies in the box.
  const long last = std::max(1L, static_cast<long>(std::floor((1.0 - h) / h + 1e-9)));
  std::vector<double> c(z.begin(), z.begin() + 2);
  for (double& x : c) x = double(std::clamp(std::lround(x / h), 1L, last)) * h;
  return c;
}

std::vector<double> study_point(const DiagnosisCampaign& c, const std::vector<double>& z) {
  if (c.grid.design != Design::local) return z;
  std::vector<double> node = lattice_point(z, c.grid.step);
  node.insert(node.end(), z.begin() + 2, z.end());
  return node;
}

namespace {

// The base model's fit on its runs so far; the centre of the box without one (the driver then
// refuses the diagnosis with the base runs' first failure).
std::vector<double> base_fit(const DiagnosisCampaign& c, const Samples& base) {
  const auto fit = fit_on_lab(c, fit_surfaces(base, 2, c.targets.size()));
  return fit ? fit->z : std::vector<double>{0.5, 0.5};
}

struct Point {
  std::size_t owner;  // 0 = the base, k = campaign candidate k - 1
  std::vector<double> z;
};

void run_into(std::vector<Samples>& samples, const std::vector<Point>& points,
              const DiagnosisCampaign& c, Evaluator& evaluator) {
  const Candidate base;
  const Numerics nominal{c.sample_seed, 1.0, 1.0};
  std::vector<RunRequest> requests;
  for (const Point& p : points) {
    requests.push_back(
        {model_point(c, p.owner == 0 ? base : c.candidates[p.owner - 1], p.z), nominal});
  }
  const std::vector<RunOutcome> outcomes = evaluator.run_batch(requests);
  for (std::size_t r = 0; r < points.size(); ++r) {
    samples[points[r].owner].z.push_back(points[r].z);
    samples[points[r].owner].outcomes.push_back(outcomes[r]);
  }
}

// One step of a walk that follows a fit: `design`'s points at `node` not yet in `made`, owned by
// `owner`; none when a design has been centred at `node` (`centres` records each).
void move_design(std::vector<Point>& points, std::size_t owner, const std::vector<double>& node,
                 std::vector<std::vector<double>>& centres, const Samples& made,
                 std::vector<std::vector<double>> design) {
  if (std::find(centres.begin(), centres.end(), node) != centres.end()) return;
  centres.push_back(node);
  for (std::vector<double>& z : design) {
    if (std::find(made.z.begin(), made.z.end(), z) == made.z.end())
      points.push_back({owner, std::move(z)});
  }
}

}  // namespace

std::vector<std::vector<double>> star(std::span<const double> z, double h) {
  const std::vector<double> c = lattice_point(z, h);
  return {c, {c[0] + h, c[1]}, {c[0] - h, c[1]}, {c[0], c[1] + h}, {c[0], c[1] - h}};
}

Samples run_local_base(const DiagnosisCampaign& c, Evaluator& evaluator) {
  std::vector<Samples> samples(1);
  std::vector<Point> grid;
  for (double x : grid_axis(c.grid.fr0)) {
    for (double y : grid_axis(c.grid.fs0)) grid.push_back({0, {x, y}});
  }
  run_into(samples, grid, c, evaluator);

  // The grid's surfaces can place the fit far from where its star's runs then put it (a coarse
  // grid over a wide box, corners without a peak): the star walks to the new node, at most
  // kStarMoves times, re-running no point it has, until the fit's node is one it centred a star on.
  std::vector<std::vector<double>> centres;
  for (int move = 0; move <= kStarMoves; ++move) {
    const std::vector<double> centre = lattice_point(base_fit(c, samples[0]), c.grid.step);
    std::vector<Point> around;
    move_design(around, 0, centre, centres, samples[0], star(centre, c.grid.step));
    if (around.empty()) break;
    run_into(samples, around, c, evaluator);
  }
  return samples[0];
}

namespace {

// One effect's design points with its strengths at `at` (nodes): a continuous effect's level s at
// at(s), its arms at s = 1 around at(1); a jumping effect's star at each level and a corner, all
// around at(1).
template <typename At>
std::vector<std::vector<double>> effect_design(const DiagnosisCampaign& c, const Candidate& k,
                                               At at) {
  const double h = c.grid.step;
  std::vector<std::vector<double>> out;
  const std::vector<double> z1 = at(1.0);
  if (k.shares_base_grid()) {
    for (double s : grid_axis(c.grid.s)) {
      if (s <= kEffectOffBelow) continue;
      const std::vector<double> z = at(s);
      out.push_back({z[0], z[1], s});
    }
    out.push_back({z1[0] + h, z1[1], 1.0});
    out.push_back({z1[0], z1[1] + h, 1.0});
  } else {
    // No base slice to lean on (its u = 0 is not the base model): a star at every level, and
    // one corner, without which the strengths' cross term is undetermined (on a star's points
    // (x - x0)(y - y0) is 0 throughout).
    for (double u : grid_axis(c.grid.s)) {
      for (const std::vector<double>& z : star(z1, h)) out.push_back({z[0], z[1], u});
    }
    out.push_back({z1[0] + h, z1[1] + h, 0.5});
  }
  return out;
}

// An effect's fit on its runs so far, with the base slice when it shares it.
std::optional<SurfaceCalibration> effect_fit(const DiagnosisCampaign& c, const Candidate& k,
                                             Samples runs, const Samples& base) {
  if (k.shares_base_grid()) append_base_slice(runs, base);
  return fit_on_lab(c, fit_surfaces(runs, k.dims(), c.targets.size()));
}

}  // namespace

void run_local_effects(const DiagnosisCampaign& c, Evaluator& evaluator,
                       std::vector<Samples>& samples,
                       const std::vector<std::array<double, 2>>& fit_shifts) {
  const double h = c.grid.step;
  samples.resize(1 + c.candidates.size());
  // The fit on grid and star: the star's runs pin the surfaces' slope and curvature there.
  const std::vector<double> z0 = lattice_point(base_fit(c, samples[0]), h);
  // First at the screen's re-fit: a continuous effect's level s at the node of the base fit +
  // s x its shift (the path its fit takes as the effect grows); a jumping effect's at the full
  // shift, its jump being there from the floor on.
  std::vector<std::vector<std::vector<double>>> centres(c.candidates.size());
  std::vector<Point> points;
  for (std::size_t k = 0; k < c.candidates.size(); ++k) {
    const std::array<double, 2> shift = k < fit_shifts.size() ? fit_shifts[k] : std::array{0., 0.};
    const bool path = c.candidates[k].shares_base_grid();
    auto at = [&](double s) {
      const double f = path ? s : 1.0;
      return lattice_point(std::vector<double>{z0[0] + f * shift[0], z0[1] + f * shift[1]}, h);
    };
    // The nodes its strengths have runs at (the base slice's at s = 0 included): a fit there is
    // interpolated.
    if (path) centres[k].push_back(z0);
    for (double s : grid_axis(c.grid.s)) centres[k].push_back(at(s));
    for (std::vector<double>& z : effect_design(c, c.candidates[k], at))
      points.push_back({k + 1, std::move(z)});
  }
  run_into(samples, points, c, evaluator);
  // Then, as the base's star, the design follows the fit its runs give: while an effect's fit lies
  // at a node it has not been designed at (at most kEffectMoves times), its design there, no
  // point it has re-run. The linear re-fit is a guess where an effect changes how the peaks
  // follow the strengths (a random packing's fit from an FCC base fit on a bound).
  for (int move = 0; move < kEffectMoves; ++move) {
    points.clear();
    for (std::size_t k = 0; k < c.candidates.size(); ++k) {
      const auto fit = effect_fit(c, c.candidates[k], samples[k + 1], samples[0]);
      if (!fit) continue;
      const std::vector<double> node = lattice_point(fit->z, h);
      move_design(points, k + 1, node, centres[k], samples[k + 1],
                  effect_design(c, c.candidates[k], [&](double) { return node; }));
    }
    if (points.empty()) break;
    run_into(samples, points, c, evaluator);
  }
  share_base_slice(samples, c);
}

}  // namespace rockcal::diagnosis
