// The `sweep` campaign kind: one job per (fr0, fs0) point and test.
#pragma once

#include "orchestrator/campaign_kinds.hpp"

namespace rockcal::orch {

// {"kind": "sweep", "name": "...", "tests": ["uct", "btt"], "job": {template},
//  "grid": {"fr0": [...], "fs0": [...]}} or "points": [[fr0, fs0], ...], "realisations": N
//  (default 1: point and test run on seeds s, s + 1, ..., s + N - 1, s the template's sample.seed).
CampaignPlan plan_sweep(const nlohmann::json& request, const Limits& limits);

CampaignKind sweep_kind();

}  // namespace rockcal::orch
