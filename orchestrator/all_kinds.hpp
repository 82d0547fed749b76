// The one list of campaign kinds the service offers: sweep, calibration, diagnosis and twin. A
// new kind is added here (and its library linked to rockcal_campaign_kinds), nowhere else.
#pragma once

#include "orchestrator/campaign_kinds.hpp"

namespace rockcal::orch {

// Adds every kind to `kinds` (JobService::kinds(), before start()).
void add_all_kinds(KindRegistry& kinds);

}  // namespace rockcal::orch
