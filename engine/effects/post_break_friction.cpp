// post_break_friction: the friction between particles whose bond has broken. Fresh crack faces in
// rock are rough, or smooth once sheared; the residual strength after the peak depends on it.
#include "engine/effects/effect.hpp"
#include "engine/simulation.hpp"
#include "engine/spec.hpp"

namespace rockcal {

EffectDef post_break_friction_effect() {
  EffectDef e;
  e.name = "post_break_friction";
  e.doc =
      "Coulomb coefficient of the contacts between particles whose bond broke (flaws' pre-cut "
      "bonds included); contacts between particles never bonded keep contact.friction, which is "
      "also the base model's value for both.";
  e.params = {{.name = "mu",
               .unit = "",
               .lo = 0.0,
               .hi = 2.0,
               .neutral = ContactSpec{}.friction,  // the default job's contact.friction
               .strong = 0.05,
               .log_scale = false,
               .doc = "Coulomb coefficient between particles whose bond broke",
               .neutral_of = [](const JobSpec& job) { return job.contact.friction; }}};
  e.defaults = {0.1};
  e.apply_specimen = [](Simulation& sim, const JobSpec&, const EffectValues& v) {
    sim.contact.broken_friction = v.at("mu");
  };
  return e;
}

}  // namespace rockcal
