// interaction_range: bonds beyond touching neighbours. A bonded-sphere model whose bonds join only
// touching spheres has a low coordination number and rolls and slides apart too easily in
// compression: its UCS/BTS ratio and friction angle stay below rock's. Bonding every pair within
// a factor of the touching distance (YADE's JCFpm "intRadius", typically 1.2-1.5) adds the
// interlocking of real grains through longer, inclined bonds.
//
// A longer bond of the same section is a longer elastic beam: softer in tension by its length
// (PFC's parallel bond, k = E A / L) and more so in bending. Bonds as stiff as touching ones make
// the lattice's second neighbours (along the cube axes in FCC) resist the lateral expansion, and
// its Poisson's ratio falls below what any shear stiffness restores (0.14 at range 1.5 with K_s
// near zero, against a rock's 0.2-0.3). `stiffness_exponent` n scales each bond's four
// stiffnesses by ((R_i + R_j) / L)^n: 0 keeps them (the base model), 1 is the beam's 1/L.
#include <cmath>

#include "engine/effects/effect.hpp"
#include "engine/simulation.hpp"
#include "engine/spec.hpp"

namespace rockcal {
namespace {

void soften_long_bonds(Simulation& sim, const JobSpec&, const EffectValues& v) {
  const double n = v.at("stiffness_exponent");
  if (n == 0.0) return;
  const Particles& p = sim.particles;
  // Decided from the bond's own rest length and radii: both ranks holding a border bond agree.
  for (Bond& b : sim.bonds) {
    const double touching =
        p.radius[static_cast<std::size_t>(b.i)] + p.radius[static_cast<std::size_t>(b.j)];
    if (b.r0 <= touching) continue;
    const double w = std::pow(touching / b.r0, n);
    b.kr *= w;
    b.ks *= w;
    b.kb *= w;
    b.kt *= w;
  }
}

// Where bonding beyond touching begins: in an FCC lattice at the second neighbours, sqrt(2) x the
// touching distance (1% past it, clear of rounding in the lattice's turned coordinates); in a
// random packing at any factor above 1.
double second_neighbours(const JobSpec& job) {
  return job.sample.packing == "fcc" ? std::sqrt(2.0) * 1.01 : 1.0;
}

// In an FCC lattice the neighbours lie in shells at sqrt(n) x the touching distance (n = 1, 2, 3,
// 4 up to the documented range's factor 2), so every factor from one shell up to the next bonds
// the same network. A random packing's count grows with any factor.
ValueSpan lattice_shell(const JobSpec& job, double factor) {
  if (job.sample.packing != "fcc") return {factor, factor};
  const double n = std::floor(factor * factor);
  return {std::sqrt(n), std::sqrt(n + 1.0)};
}

}  // namespace

EffectDef interaction_range_effect() {
  EffectDef e;
  e.name = "interaction_range";
  e.doc =
      "Bonds join every pair whose centres lie within factor x (R_i + R_j), not only touching "
      "ones; each bond keeps its rest length and the job's strengths, and its stiffnesses times "
      "((R_i + R_j) / L)^n for its rest length L (n = 0: the job's). In an FCC lattice the second "
      "neighbours join from factor sqrt(2) = 1.414 (18 bonds a particle instead of 12), the third "
      "from sqrt(3) = 1.732; in a random packing the count grows steadily from 1.";
  e.params = {{.name = "factor",
               .unit = "",
               .lo = 1.0,
               .hi = 2.0,
               .neutral = 1.0,
               .strong = 1.5,
               .log_scale = false,
               .doc = "bonding distance / touching distance",
               // FCC: nothing changes below sqrt(2), then a sixth of the bonds at once.
               .continuous_at_neutral = false,
               .first_change_of = second_neighbours,
               .same_model_of = lattice_shell},
              {.name = "stiffness_exponent",
               .unit = "",
               .lo = 0.0,
               .hi = 8.0,
               .neutral = 0.0,
               .strong = 2.0,
               .log_scale = false,
               .doc = "n in the stiffness factor ((R_i + R_j) / L)^n of a bond of rest length L"}};
  e.defaults = {1.5, 0.0};
  e.apply_spec = [](JobSpec& spec, const EffectValues& v) { spec.bond.reach = v.at("factor"); };
  e.apply_specimen = soften_long_bonds;
  return e;
}

}  // namespace rockcal
