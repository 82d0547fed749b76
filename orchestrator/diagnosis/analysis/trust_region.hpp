// Step control of the refinement by real runs: a backtracking trust region in the unit cube.
#pragma once

#include <limits>
#include <optional>
#include <vector>

namespace rockcal::diagnosis {

struct TrustRegion {
  explicit TrustRegion(double first_radius) : radius(first_radius) {}

  double radius;  // longest step (max norm, unit cube) the next trial may take from the best
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_z, best_ln;

  // A run made before the refinement (the design's): the start when it is the best so far; the
  // radius is kept.
  void start_from(const std::vector<double>& z, double misfit, const std::vector<double>& ln);
  // The trial at z with its real misfit and values; true when it is the new best. After a worse
  // trial the radius becomes half its distance from the best: the surface was not to be trusted
  // so far.
  bool record(const std::vector<double>& z, double misfit, const std::vector<double>& ln);
  // The next trial on the way from best_z to `target` (the re-fit from the best run), at most
  // `radius` from best_z; nullopt once settled (radius or the re-fit's move below `settled`).
  std::optional<std::vector<double>> next(const std::vector<double>& target, double settled);
};

}  // namespace rockcal::diagnosis
