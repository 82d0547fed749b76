#include "api/optional_kinds.hpp"

#ifdef ROCKCAL_WITH_CALIBRATION
#include "orchestrator/calibration/calibration_kind.hpp"
#endif

namespace rockcal::api {

void register_optional_kinds([[maybe_unused]] orch::JobService& service) {
#ifdef ROCKCAL_WITH_CALIBRATION
  service.kinds().add(rockcal::calibration::calibration_kind());
#endif
}

}  // namespace rockcal::api
