// heterogeneity: bond strengths scattered about the job's values. Rock grains and cements vary; a
// uniform lattice of equal bonds fails too abruptly and too strongly in compression against
// tension.
#include <cmath>
#include <limits>

#include "engine/effects/draw.hpp"
#include "engine/effects/effect.hpp"
#include "engine/simulation.hpp"
#include "engine/spec.hpp"

namespace rockcal {
namespace {

constexpr std::uint64_t kStream = 0x6865746572;  // "heter": keeps these draws apart from flaws'

// Weibull draw of shape m scaled to mean 1 (scale 1 / Gamma(1 + 1/m)), by its inverse CDF.
double strength_multiplier(double m, double scale, std::uint64_t seed, const Bond& b) {
  const double u = effects::unit_draw(seed, kStream, static_cast<std::uint64_t>(b.id_i),
                                      static_cast<std::uint64_t>(b.id_j));
  return scale * std::pow(-std::log1p(-u), 1.0 / m);
}

void scatter_strengths(Simulation& sim, const JobSpec& spec, const EffectValues& v) {
  const double m = v.at("weibull_m");
  const double scale = 1.0 / std::tgamma(1.0 + 1.0 / m);
  // One multiplier per bond for all four strengths: the seed ties G_b0 and G_t0 to F_r0 and F_s0,
  // and a weak cement is weak in every mode. Drawn from the bond's global ids and the job seed, so
  // both ranks holding a border bond scale it alike.
  for (Bond& b : sim.bonds) {
    const double w = strength_multiplier(m, scale, spec.sample.seed, b);
    set_strengths(b, b.fr0 * w, b.fs0 * w, b.gb0 * w, b.gt0 * w);
  }
}

}  // namespace

EffectDef heterogeneity_effect() {
  EffectDef e;
  e.name = "heterogeneity";
  e.doc =
      "Per-bond strength multipliers from a Weibull distribution of modulus weibull_m, scaled to "
      "mean 1 (coefficient of variation 0.28 at m = 4, 0.52 at m = 2): each bond's F_r0, F_s0, "
      "G_b0 and G_t0 are multiplied by its own draw, a function of the job seed and the bond's "
      "particle ids.";
  e.params = {{.name = "weibull_m",
               .unit = "",
               .lo = 1.2,
               .hi = 50.0,
               .neutral = std::numeric_limits<double>::infinity(),  // no scatter: walk 1 / m
               .strong = 2.0,
               .log_scale = false,
               .doc = "Weibull modulus of the bond strength multipliers"}};
  e.defaults = {4.0};
  e.apply_specimen = scatter_strengths;
  e.draws_from_seed = true;
  return e;
}

}  // namespace rockcal
