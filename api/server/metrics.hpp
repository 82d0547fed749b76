// /metrics in the Prometheus text format: jobs by state, queue length, job durations, and per
// executor its queue depth, running jobs, jobs pending in its scheduler and failures by reason.
#pragma once

#include <string>

#include "orchestrator/job_service.hpp"

namespace rockcal::api {

std::string metrics_text(orch::JobService& service, int workers);

}  // namespace rockcal::api
