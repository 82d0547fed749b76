#include "api/optional_kinds.hpp"

#ifdef ROCKCAL_WITH_CALIBRATION
#include "orchestrator/calibration/calibration_kind.hpp"
#endif
#ifdef ROCKCAL_WITH_DIAGNOSIS
#include "orchestrator/diagnosis/diagnosis_kind.hpp"
#include "orchestrator/diagnosis/twin/twin_kind.hpp"
#endif

namespace rockcal::api {

void register_optional_kinds([[maybe_unused]] orch::JobService& service) {
#ifdef ROCKCAL_WITH_CALIBRATION
  service.kinds().add(rockcal::calibration::calibration_kind());
#endif
#ifdef ROCKCAL_WITH_DIAGNOSIS
  service.kinds().add(rockcal::diagnosis::diagnosis_kind());
  service.kinds().add(rockcal::diagnosis::twin_kind());
#endif
}

}  // namespace rockcal::api
