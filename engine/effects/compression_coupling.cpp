// compression_coupling: how much a bond's compression raises its capacity for shear, twist and
// bending in eq. 2. The seed's rule (signed f_r) makes compressed bonds very hard to break, which
// inflates the UCS against the BTS; clamping f_r at zero is the other common choice.
#include "engine/effects/effect.hpp"
#include "engine/simulation.hpp"

namespace rockcal {

EffectDef compression_coupling_effect() {
  EffectDef e;
  e.name = "compression_coupling";
  e.doc =
      "Sets the break rule's compression coupling: eq. 2 uses coupling x f_r for a compressive "
      "f_r (1 = the seed's signed f_r, compression raises the other terms' capacity; 0 = f_r "
      "clamped at zero). Tension is unaffected.";
  e.params = {{.name = "coupling",
               .unit = "",
               .lo = 0.0,
               .hi = 1.0,
               .neutral = 1.0,
               .strong = 0.0,
               .log_scale = false,
               .doc = "weight of a compressive normal force in eq. 2"}};
  e.defaults = {0.0};
  e.apply_specimen = [](Simulation& sim, const JobSpec&, const EffectValues& v) {
    sim.break_rule.compression_coupling = v.at("coupling");
  };
  return e;
}

}  // namespace rockcal
