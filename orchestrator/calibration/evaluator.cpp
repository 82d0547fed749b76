#include "orchestrator/calibration/evaluator.hpp"

namespace rockcal::calibration {

nlohmann::json job_for(const nlohmann::json& job_template, const EvaluationRequest& request,
                       TestKind test) {
  nlohmann::json job = job_template;
  job["test"] = to_string(test);
  job["bond"] = {{"fr0", request.point.fr0_n}, {"fs0", request.point.fs0_n}};
  job["sample"]["seed"] = request.sample_seed;
  // Canonical form: equal requests give byte-equal jobs, so the job cache recognises them.
  return to_json(parse_job(job));
}

}  // namespace rockcal::calibration
