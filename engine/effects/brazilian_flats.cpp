// brazilian_flats: the lab loaded its discs through flats of another width. A Brazilian disc's
// peak load depends on how the platens meet it: a line contact crushes the rim before the centre
// splits, a wide flat spreads the load and carries more. The lab's set-up (curved jaws, flats cut
// on the disc, cardboard cushions) is often not the model's, and the seed paper's ratio gap may be
// part test set-up rather than rock: this effect loads the model's discs through flats of the
// given loading angle 2 alpha (Wang et al. 2004), so the diagnosis can ask whether another contact
// width explains the BTT.
#include "engine/effects/effect.hpp"
#include "engine/spec.hpp"

namespace rockcal {

EffectDef brazilian_flats_effect() {
  EffectDef e;
  e.name = "brazilian_flats";
  e.doc =
      "The BTT disc is loaded through flats of loading angle 2 alpha = angle_deg (sets "
      "loading.btt_geometry = \"flattened\" and loading.flat_angle_deg; the strength carries Wang "
      "et al.'s factor k). Other tests are unchanged. Neutral is the job's own angle when its "
      "discs are flattened; from flat platens or curved jaws any angle switches the set-up.";
  e.params = {{.name = "angle_deg",
               .unit = "deg",
               .lo = 5.0,
               .hi = 60.0,
               .neutral = LoadingSpec{}.flat_angle_deg,  // the default job's flats
               .strong = 10.0,  // the narrowest contact: the ISRM jaws' arc at failure
               .log_scale = false,
               .doc = "loading angle 2 alpha of the disc's flats",
               .neutral_of =
                   [](const JobSpec& job) {
                     return job.loading.btt_geometry == BttGeometry::flattened
                                ? job.loading.flat_angle_deg
                                : LoadingSpec{}.flat_angle_deg;
                   },
               // A job with flat platens or curved jaws has no angle to walk from.
               .continuous_at_neutral = false}};
  e.defaults = {20.0};
  e.apply_spec = [](JobSpec& spec, const EffectValues& v) {
    if (spec.test != TestKind::btt) return;
    spec.loading.btt_geometry = BttGeometry::flattened;
    spec.loading.flat_angle_deg = v.at("angle_deg");
  };
  return e;
}

}  // namespace rockcal
