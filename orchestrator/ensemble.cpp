#include "orchestrator/ensemble.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rockcal::orch {

using nlohmann::json;

int realisation_count(const json* value) {
  if (!value) return 1;
  if (!value->is_number_integer() || value->get<double>() < 1 ||
      value->get<double>() > kMaxRealisations) {
    throw std::invalid_argument("must be an integer in [1, " + std::to_string(kMaxRealisations) +
                                "]");
  }
  return int(value->get<std::int64_t>());
}

std::vector<std::uint64_t> realisation_seeds(std::uint64_t base_seed, int count) {
  std::vector<std::uint64_t> seeds;
  for (int k = 0; k < count; ++k) seeds.push_back(base_seed + std::uint64_t(k));
  return seeds;
}

std::optional<std::string> realisations_problem(int count, std::uint64_t base_seed,
                                                bool seed_matters) {
  constexpr auto largest = std::uint64_t(std::numeric_limits<std::int64_t>::max());
  if (base_seed > largest - std::uint64_t(count - 1)) {
    return "sample.seed + realisations - 1 exceeds the largest seed, " + std::to_string(largest);
  }
  if (count > 1 && !seed_matters) {
    return "the template's specimen is the same under every seed (an aligned FCC lattice without "
           "seeded effects): more than one realisation would repeat one run";
  }
  return std::nullopt;
}

double relative_se(const SampleStats& s) {
  return s.se && s.mean && *s.mean > 0 ? *s.se / *s.mean : 0.0;
}

SampleStats sample_stats(const std::vector<double>& values) {
  SampleStats s;
  s.n = int(values.size());
  if (values.empty()) return s;
  double sum = 0.0;
  for (double v : values) sum += v;
  const double mean = sum / double(values.size());
  s.mean = mean;
  if (values.size() < 2) return s;
  double ss = 0.0;
  for (double v : values) ss += (v - mean) * (v - mean);
  s.sd = std::sqrt(ss / double(values.size() - 1));
  s.se = *s.sd / std::sqrt(double(values.size()));
  return s;
}

Ensemble make_ensemble(std::vector<Realisation> realisations) {
  std::stable_sort(realisations.begin(), realisations.end(),
                   [](const Realisation& a, const Realisation& b) { return a.seed < b.seed; });
  Ensemble e;
  std::vector<double> peak, strength, modulus;
  for (const Realisation& r : realisations) {
    if (r.state == "failed" || r.state == "cancelled") ++e.failed;
    if (r.state != "succeeded") continue;
    if (r.peak_load_n) peak.push_back(*r.peak_load_n);
    if (r.strength_pa) strength.push_back(*r.strength_pa);
    if (r.youngs_modulus_pa) modulus.push_back(*r.youngs_modulus_pa);
  }
  e.peak_load = sample_stats(peak);
  e.strength = sample_stats(strength);
  e.modulus = sample_stats(modulus);
  e.realisations = std::move(realisations);
  return e;
}

namespace {

json or_null(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? json(*v) : json(nullptr);
}

}  // namespace

json to_json(const SampleStats& s) {
  return {{"mean", or_null(s.mean)}, {"sd", or_null(s.sd)}, {"se", or_null(s.se)}, {"n", s.n}};
}

json to_json(const Ensemble& e) {
  json runs = json::array();
  for (const Realisation& r : e.realisations) {
    runs.push_back({{"seed", r.seed},
                    {"job_id", r.job_id > 0 ? json(r.job_id) : json(nullptr)},
                    {"state", r.state},
                    {"peak_load_n", or_null(r.peak_load_n)},
                    {"strength_pa", or_null(r.strength_pa)},
                    {"youngs_modulus_pa", or_null(r.youngs_modulus_pa)},
                    {"quasi_static", r.quasi_static ? json(*r.quasi_static) : json(nullptr)},
                    {"poisson_ratio", or_null(r.poisson_ratio)},
                    {"error", r.error.empty() ? json(nullptr) : json(r.error)}});
  }
  return {{"realisations", runs},
          {"peak_load", to_json(e.peak_load)},
          {"strength", to_json(e.strength)},
          {"modulus", to_json(e.modulus)},
          {"failed", e.failed}};
}

}  // namespace rockcal::orch
