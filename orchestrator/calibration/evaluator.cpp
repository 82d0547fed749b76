#include "orchestrator/calibration/evaluator.hpp"

namespace rockcal::calibration {

namespace {

nlohmann::json job_at(nlohmann::json job, TestKind test, const BondPoint& point,
                      std::uint64_t seed) {
  job["test"] = to_string(test);
  job["bond"] = {{"fr0", point.fr0_n}, {"fs0", point.fs0_n}};
  job["sample"]["seed"] = seed;
  // Canonical form: equal requests give byte-equal jobs, so the job cache recognises them.
  return to_json(parse_job(job));
}

}  // namespace

nlohmann::json job_for(const nlohmann::json& job_template, const EvaluationRequest& request,
                       TestKind test, std::uint64_t seed) {
  return job_at(job_template, test, request.point, seed);
}

nlohmann::json job_for(const nlohmann::json& job_template, const ProbeRequest& probe,
                       std::uint64_t seed) {
  nlohmann::json job = job_template;
  job.merge_patch(probe.patch);
  return job_at(std::move(job), probe.test, probe.point, seed);
}

namespace {

std::string first_error(const orch::Ensemble& e) {
  for (const orch::Realisation& r : e.realisations) {
    if (!r.error.empty()) return r.error;
  }
  return "";
}

}  // namespace

EvaluationOutcome outcome_of(orch::Ensemble uct, orch::Ensemble btt) {
  EvaluationOutcome out;
  if (uct.peak_load.mean && btt.peak_load.mean) {
    out.loads = PeakLoads{*uct.peak_load.mean, *btt.peak_load.mean};
  } else {
    const bool uct_missing = !uct.peak_load.mean;
    const std::string why = first_error(uct_missing ? uct : btt);
    out.error = std::string(uct_missing ? "uct: " : "btt: ") +
                (why.empty() ? "no realisation reported a peak load" : why);
  }
  out.uct = std::move(uct);
  out.btt = std::move(btt);
  return out;
}

}  // namespace rockcal::calibration
