// interaction_range: bonds beyond touching neighbours. A bonded-sphere model whose bonds join only
// touching spheres has a low coordination number and rolls and slides apart too easily in
// compression: its UCS/BTS ratio and friction angle stay below rock's. Bonding every pair within
// a factor of the touching distance (YADE's JCFpm "intRadius", typically 1.2-1.5) adds the
// interlocking of real grains through longer, inclined bonds.
#include "engine/effects/effect.hpp"
#include "engine/spec.hpp"

namespace rockcal {

EffectDef interaction_range_effect() {
  EffectDef e;
  e.name = "interaction_range";
  e.doc =
      "Bonds join every pair whose centres lie within factor x (R_i + R_j), not only touching "
      "ones; each bond keeps its rest length, the job's stiffness and strengths. In an FCC lattice "
      "the second neighbours join from factor sqrt(2) = 1.414 (18 bonds a particle instead of 12), "
      "the third from sqrt(3) = 1.732; in a random packing the count grows steadily from 1.";
  e.params = {{.name = "factor",
               .unit = "",
               .lo = 1.0,
               .hi = 2.0,
               .neutral = 1.0,
               .strong = 1.5,
               .log_scale = false,
               .doc = "bonding distance / touching distance",
               // FCC: nothing changes below sqrt(2), then a sixth of the bonds at once.
               .continuous_at_neutral = false}};
  e.defaults = {1.5};
  e.apply_spec = [](JobSpec& spec, const EffectValues& v) { spec.bond.reach = v.at("factor"); };
  return e;
}

}  // namespace rockcal
