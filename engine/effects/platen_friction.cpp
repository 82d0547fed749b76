// platen_friction: friction between the platens and the specimen's ends. Lab platens are rarely
// frictionless; end friction confines the ends and raises the apparent UCS.
#include "engine/effects/effect.hpp"
#include "engine/spec.hpp"

namespace rockcal {

EffectDef platen_friction_effect() {
  EffectDef e;
  e.name = "platen_friction";
  e.doc =
      "Coulomb friction between the platens and the particles they touch: sets "
      "loading.platen_friction = mu (the base model's platens are frictionless).";
  e.params = {{.name = "mu",
               .unit = "",
               .lo = 0.0,
               .hi = 1.0,
               .neutral = 0.0,
               .strong = 0.5,
               .log_scale = false,
               .doc = "platen-particle Coulomb coefficient"}};
  e.defaults = {0.3};
  e.apply_spec = [](JobSpec& spec, const EffectValues& v) {
    spec.loading.platen_friction = v.at("mu");
  };
  return e;
}

}  // namespace rockcal
