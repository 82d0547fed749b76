#include "engine/loadtests/brazilian.hpp"

#include <algorithm>
#include <cmath>

namespace rockcal {

namespace {
double half_loading_angle(const LoadingSpec& l) {
  return 0.5 * l.flat_angle_deg * M_PI / 180.0;
}
}  // namespace

Disc btt_disc(const JobSpec& spec) {
  Disc d{spec.sample.diameter_m, spec.sample.btt_thickness()};
  if (spec.loading.btt_geometry == BttGeometry::flattened)
    d.flat_z_m = 0.5 * spec.sample.diameter_m * std::cos(half_loading_angle(spec.loading));
  return d;
}

double btt_strength_factor(const LoadingSpec& loading) {
  if (loading.btt_geometry != BttGeometry::flattened) return 1.0;
  const double a = half_loading_angle(loading);
  const double c = std::cos(a), s = std::sin(a);
  const double num = 2.0 * c * c * c + c + s / a;
  return num * num / (8.0 * (c + s / a)) * a / s;
}

BttFracture btt_fracture(const JobSpec& spec, const std::vector<BreakEvent>& breaks,
                         std::int64_t from_step, std::int64_t peak_step) {
  const double radius = 0.5 * spec.sample.diameter_m;
  const double interior = 1.0 - 2.0 * spec.sample.radius_m / radius;
  BttFracture f;
  std::vector<double> first;
  std::int64_t counted = 0, in_band = 0;
  for (const BreakEvent& e : breaks) {
    if (e.step < from_step) continue;
    ++counted;
    if (std::abs(e.where.x()) <= kLoadedBandHalfWidth * radius) ++in_band;
    const double r = std::hypot(e.where.x(), e.where.z()) / radius;
    if (r > interior)
      f.rim_breaks_before_peak += e.step <= peak_step ? 1 : 0;
    else if (first.size() < static_cast<std::size_t>(kFirstBreaks))
      first.push_back(r);
  }
  if (counted > 0)
    f.loaded_band_fraction = static_cast<double>(in_band) / static_cast<double>(counted);
  if (first.empty()) return f;
  f.first_count = static_cast<std::int64_t>(first.size());
  f.first_max_r_over_R = *std::max_element(first.begin(), first.end());
  std::sort(first.begin(), first.end());
  const std::size_t n = first.size();
  f.first_median_r_over_R = n % 2 ? first[n / 2] : 0.5 * (first[n / 2 - 1] + first[n / 2]);
  f.centre_split = f.first_median_r_over_R <= kCentreSplitRadius;
  return f;
}

}  // namespace rockcal
