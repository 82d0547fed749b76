// rate: the platens move faster than the job says. DEM loading is far faster than the lab's; an
// inertial strength gain is a numerical gap that looks like a stronger rock.
#include "engine/effects/effect.hpp"
#include "engine/spec.hpp"

namespace rockcal {

EffectDef rate_effect() {
  EffectDef e;
  e.name = "rate";
  e.doc =
      "Multiplies loading.platen_velocity by speed_factor (the job's platen speed stays in the "
      "job as written, so the canonical form does not compound it); an \"auto\" speed through "
      "loading.auto_transits, divided by the factor.";
  e.params = {{.name = "speed_factor",
               .unit = "",
               .lo = 0.125,
               .hi = 16.0,
               .neutral = 1.0,
               .strong = 8.0,
               .log_scale = true,
               .doc = "platen speed / the job's platen speed"}};
  e.defaults = {4.0};
  e.apply_spec = [](JobSpec& spec, const EffectValues& v) {
    if (spec.loading.platen_velocity_m_s)
      *spec.loading.platen_velocity_m_s *= v.at("speed_factor");
    else
      spec.loading.auto_transits /= v.at("speed_factor");
  };
  return e;
}

}  // namespace rockcal
