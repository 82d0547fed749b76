#include "orchestrator/sweep.hpp"

#include <utility>

#include "engine/effects/effect.hpp"
#include "engine/spec.hpp"
#include "orchestrator/ensemble.hpp"
#include "orchestrator/job_identity.hpp"
#include "orchestrator/json_fields.hpp"
#include "orchestrator/request_error.hpp"
#include "orchestrator/request_fields.hpp"

namespace rockcal::orch {
namespace {

using nlohmann::json;
using Point = std::pair<double, double>;

std::vector<Point> grid_points(const json& grid, std::size_t cap) {
  if (!grid.is_object())
    throw RequestError("grid", "must be an object {\"fr0\": [...], \"fs0\": [...]}");
  JsonFields f(grid, "grid");
  auto fr0 = positive_numbers(f.require("fr0"), "grid.fr0", cap);
  auto fs0 = positive_numbers(f.require("fs0"), "grid.fs0", cap);
  f.reject_unknown();
  // Both sizes are <= cap, so the product cannot overflow.
  if (fr0.size() * fs0.size() > cap) {
    throw RequestError("grid", "has " + std::to_string(fr0.size() * fs0.size()) +
                                   " points; the cap is " + std::to_string(cap));
  }
  std::vector<Point> out;
  for (double r : fr0) {
    for (double s : fs0) out.emplace_back(r, s);
  }
  return out;
}

std::vector<Point> listed_points(const json& points, std::size_t cap) {
  if (!points.is_array() || points.empty()) {
    throw RequestError("points", "must be a non-empty array of [fr0, fs0] pairs");
  }
  if (points.size() > cap) {
    throw RequestError("points", "has " + std::to_string(points.size()) + " points; the cap is " +
                                     std::to_string(cap));
  }
  std::vector<Point> out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::string field = "points[" + std::to_string(i) + "]";
    const json& p = points[i];
    if (!p.is_array() || p.size() != 2) throw RequestError(field, "must be a pair [fr0, fs0]");
    out.emplace_back(positive_number(p[0], field + "[0]"), positive_number(p[1], field + "[1]"));
  }
  return out;
}

// The template's seed (from `first`, the first job), once `count` realisations are checked
// against it.
std::uint64_t base_seed(int count, const rockcal::JobSpec& spec) {
  if (auto problem = realisations_problem(count, spec.sample.seed, rockcal::seed_matters(spec))) {
    throw RequestError("realisations", *problem);
  }
  return spec.sample.seed;
}

}  // namespace

CampaignPlan plan_sweep(const json& request, const Limits& limits) {
  JsonFields f(request, "");
  for (const char* key : {"kind", "name", "tests", "job", "grid", "points", "realisations"}) {
    f.get(key);
  }
  // Unknown keys first: a typo must not be reported as some other field's error.
  f.reject_unknown();
  CampaignPlan plan;
  plan.name = campaign_name(request, "sweep");
  auto tests = test_names(request);
  const json& tmpl = job_template(request);
  if (request.contains("grid") == request.contains("points")) {
    throw RequestError("grid", "give exactly one of \"grid\" and \"points\"");
  }
  int realisations = 1;
  try {
    realisations =
        realisation_count(request.contains("realisations") ? &request["realisations"] : nullptr);
  } catch (const std::invalid_argument& e) {
    throw RequestError("realisations", e.what());
  }
  std::size_t cap = limits.max_jobs_per_campaign;
  auto points = request.contains("grid") ? grid_points(request["grid"], cap)
                                         : listed_points(request["points"], cap);
  // points and tests are each <= cap and realisations <= kMaxRealisations: no overflow.
  const std::size_t jobs = points.size() * tests.size() * std::size_t(realisations);
  if (jobs > cap) {
    throw RequestError(
        request.contains("grid") ? "grid" : "points",
        std::to_string(jobs) + " jobs exceed the cap of " + std::to_string(cap) + " per campaign");
  }
  // The template is validated once per test as it stands (the request's JSON is never copied);
  // each job is the parsed spec with its point's strengths, and every job goes through the
  // engine's validation again before anything is stored. Realisation k of a point runs seed s + k,
  // s the template's: its own job, so the cache knows it.
  for (const auto& test : tests) {
    rockcal::JobSpec base;
    try {
      const rockcal::BondSpec first{points.front().first, points.front().second};
      base = rockcal::parse_job_template(tmpl, *rockcal::test_kind_from_string(test), first);
    } catch (const rockcal::SpecError& e) {
      throw under("job", e);
    }
    const auto seeds = realisation_seeds(base_seed(realisations, base), realisations);
    for (auto [fr0, fs0] : points) {
      base.bond = {fr0, fs0};
      for (std::uint64_t seed : seeds) {
        base.sample.seed = seed;
        plan.jobs.push_back(make_job(rockcal::to_json(base), "job."));
      }
    }
  }
  return plan;
}

CampaignKind sweep_kind() {
  return {"sweep", plan_sweep, nullptr, nullptr};
}

}  // namespace rockcal::orch
