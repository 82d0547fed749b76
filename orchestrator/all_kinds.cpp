#include "orchestrator/all_kinds.hpp"

#include "orchestrator/calibration/calibration_kind.hpp"
#include "orchestrator/diagnosis/diagnosis_kind.hpp"
#include "orchestrator/diagnosis/twin/twin_kind.hpp"
#include "orchestrator/sweep.hpp"

namespace rockcal::orch {

void add_all_kinds(KindRegistry& kinds) {
  kinds.add(sweep_kind());
  kinds.add(calibration::calibration_kind());
  kinds.add(diagnosis::diagnosis_kind());
  kinds.add(diagnosis::twin_kind());
}

}  // namespace rockcal::orch
