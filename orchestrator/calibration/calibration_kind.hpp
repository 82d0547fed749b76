// The campaign kind "calibration" for the service (listed in orchestrator/all_kinds.cpp). Its plan
// validates the whole campaign (400 naming the field) and creates no jobs up front; its driver
// thread runs the calibration on the pool and returns the report JSON.
#pragma once

#include "orchestrator/campaign_kinds.hpp"

namespace rockcal::calibration {

orch::CampaignKind calibration_kind();

}  // namespace rockcal::calibration
