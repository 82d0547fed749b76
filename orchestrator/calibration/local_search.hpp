// The generic 2-D search: NLopt on (ln F_r0, ln F_s0), normalised to the unit square so that both
// axes have the same scale for the trust region / simplex.
#pragma once

#include "orchestrator/calibration/ledger.hpp"

namespace rockcal::calibration {

// Minimises the misfit from `start` with the campaign's algorithm. Returns when NLopt converges;
// throws SearchDone / EvaluationCancelled like the ledger.
void local_search(Ledger& ledger, const CalibrationCampaign& campaign, const BondPoint& start);

}  // namespace rockcal::calibration
