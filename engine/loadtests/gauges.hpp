// Strain gauges of a compression test, as a lab's over the specimen's middle: the interior's
// strain (interior_strain, measure_interior's strain, over the central half: the elastic test's
// region) read along the loading, and the Poisson's ratio and modulus they give over the pre-peak
// modulus window.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "engine/loadtests/interior.hpp"
#include "engine/loadtests/result.hpp"

namespace rockcal {

struct GaugeReading {
  std::size_t row;  // the curve row it was read at
  double axial;    // the interior's axial strain since the gauges were placed, compression positive
  double lateral;  // its mean lateral strain, the same sign convention (expansion negative)
};

struct Gauges {
  std::unordered_map<std::int64_t, Vec3> reference;  // the interior's owned particles, by id
  CentralHalf region;
  InteriorScratch scratch;
  std::vector<GaugeReading> readings;  // reserved up front: reading does not allocate
};

// Gauges on the specimen's central half at the particles' current positions, with room for
// `max_readings` readings. Under decomposition a particle that later changes rank leaves the fit.
Gauges place_gauges(const Simulation& sim, const JobSpec& spec, std::size_t max_readings);

// Reads the gauges for curve row `row`. A collective: every rank reads at the same rows.
void read_gauges(const Simulation& sim, Gauges& gauges, std::size_t row);

// From the readings at the curve rows in the modulus window (modulus.hpp): Poisson's ratio,
// -d(lateral)/d(axial) of the interior, and the gauge modulus, the platen stress (load from
// `base_load` over `area_m2`) against the interior's axial strain; each a least-squares slope.
struct GaugeFit {
  std::optional<double> poisson_ratio, youngs_modulus_pa;
};
GaugeFit gauge_fit(const std::vector<GaugeReading>& readings, const std::vector<CurvePoint>& curve,
                   double base_load, double peak_load, double area_m2);

}  // namespace rockcal
