// Campaign kinds beyond the built-in sweep that this build includes (e.g. the calibration).
#pragma once

#include "orchestrator/job_service.hpp"

namespace rockcal::api {

// Registers them with the service; call before service.start().
void register_optional_kinds(orch::JobService& service);

}  // namespace rockcal::api
