// rolling_resistance: a moment at contacts against the relative rotation of the two particles.
// Rock grains are angular and interlock; smooth spheres roll over each other at no cost, which
// keeps a bonded-sphere model's friction angle and its UCS/BTS ratio low once bonds have broken.
#include "engine/effects/effect.hpp"
#include "engine/simulation.hpp"
#include "engine/spec.hpp"

namespace rockcal {

EffectDef rolling_resistance_effect() {
  EffectDef e;
  e.name = "rolling_resistance";
  e.doc =
      "Rolling resistance at the frictional contacts (between particles never bonded or whose "
      "bond broke): an elastic-plastic moment against the pair's relative rotation, stiffness "
      "2.25 k_n mu_r^2 R*^2 and limit mu_r R* F_n with R* = R_i R_j / (R_i + R_j) (Ai et al. "
      "2011). Intact bonds are unchanged; the base model's spheres roll freely (mu_r = 0).";
  e.params = {{.name = "mu_r",
               .unit = "",
               .lo = 0.0,
               .hi = 1.0,
               .neutral = 0.0,
               .strong = 0.3,
               .log_scale = false,
               .doc = "rolling friction coefficient (moment limit / (R* F_n))"}};
  e.defaults = {0.1};
  e.apply_specimen = [](Simulation& sim, const JobSpec&, const EffectValues& v) {
    sim.contact.rolling_friction = v.at("mu_r");
  };
  return e;
}

}  // namespace rockcal
