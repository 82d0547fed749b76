// packing: a random dense polydisperse packing instead of the FCC lattice. The lattice is stiffer
// and more regular than rock grains; its strength anisotropy and its single bond length are
// artefacts the diagnosis must be able to tell from a real gap.
#include "engine/effects/effect.hpp"
#include "engine/spec.hpp"

namespace rockcal {

EffectDef packing_effect() {
  EffectDef e;
  e.name = "packing";
  e.doc =
      "Random dense packing (docs/packing.md) with radii uniform between min and max, "
      "radius_ratio = max / min, instead of the FCC lattice: sets sample.packing = \"random\" and "
      "sample.radius_ratio. The neutral state is the FCC lattice, which no radius ratio gives: any "
      "value switches the packing.";
  // Neutral 1 stands for FCC (monodisperse); the diagnosis walks 1 -> 2.
  e.params = {{.name = "radius_ratio",
               .unit = "",
               .lo = 1.0,
               .hi = 3.0,
               .neutral = 1.0,
               .strong = 2.0,
               .log_scale = false,
               .doc = "max / min particle radius of the random packing",
               .continuous_at_neutral = false}};
  e.defaults = {1.5};
  e.apply_spec = [](JobSpec& spec, const EffectValues& v) {
    spec.sample.packing = "random";
    spec.sample.radius_ratio = v.at("radius_ratio");
  };
  return e;
}

}  // namespace rockcal
