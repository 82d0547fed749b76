#include "engine/loadtests/gauges.hpp"

#include "engine/loadtests/modulus.hpp"

namespace rockcal {

Gauges place_gauges(const Simulation& sim, const JobSpec& spec, std::size_t max_readings) {
  Gauges g;
  g.region = central_half(spec);
  for (std::size_t k = 0; k < sim.particles.n_owned; ++k) {
    if (g.region(sim.particles.pos[k]))
      g.reference.emplace(sim.particles.id[k], sim.particles.pos[k]);
  }
  // With headroom: on more than one rank the owned and ghost counts move as particles migrate,
  // and the curve rows that read the gauges run in the time-step loop, which must not allocate.
  g.scratch.in.reserve(2 * sim.particles.size() + 64);
  g.scratch.ref.reserve(2 * sim.particles.n_owned + 64);
  g.readings.reserve(max_readings);
  return g;
}

void read_gauges(const Simulation& sim, Gauges& gauges, std::size_t row) {
  const InteriorState s = interior_strain(sim, gauges.reference, gauges.region, gauges.scratch);
  gauges.readings.push_back(
      {row, -axial_component(s.strain), -lateral_component(s.strain)});  // to compression positive
}

GaugeFit gauge_fit(const std::vector<GaugeReading>& readings, const std::vector<CurvePoint>& curve,
                   double base_load, double peak_load, double area_m2) {
  const ModulusWindow window = modulus_window(curve, base_load, peak_load);
  LineFit lateral, stress;
  for (const GaugeReading& g : readings) {
    if (g.row >= curve.size() || !window.contains(curve, g.row)) continue;
    lateral.add(g.axial, g.lateral);
    stress.add(g.axial, (curve[g.row].load_n - base_load) / area_m2);
  }
  GaugeFit fit;
  if (const auto slope = lateral.slope()) fit.poisson_ratio = -*slope;
  fit.youngs_modulus_pa = stress.slope();
  return fit;
}

}  // namespace rockcal
