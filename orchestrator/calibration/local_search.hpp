// The generic 2-D search: NLopt on (ln F_r0, ln F_s0), normalised to the unit square so that both
// axes have the same scale for the trust region / simplex.
#pragma once

#include "orchestrator/calibration/ledger.hpp"

namespace rockcal::calibration {

// Minimises the misfit from `start` with the campaign's algorithm; `initial_step` is a fraction of
// the log box. Returns when NLopt converges; throws SearchDone / EvaluationCancelled like the
// ledger.
void local_search(Ledger& ledger, const CalibrationCampaign& campaign, const BondPoint& start,
                  double initial_step);

// local_search, restarted from the best point with a halved step while a run still improves it:
// NLopt's local methods stop when their model or simplex collapses, which the penalty of a failed
// run or noise can cause far from the target.
void local_search_with_restarts(Ledger& ledger, const CalibrationCampaign& campaign,
                                const BondPoint& start);

}  // namespace rockcal::calibration
