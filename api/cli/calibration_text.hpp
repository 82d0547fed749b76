// A calibration campaign as `rockcal status` shows it: its progress line while it runs and the
// table of its report once it has ended.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace rockcal::api {

// A live calibration's line: "campaign 3 running: 12 of 40 evaluations done (+2 seed re-runs),
// best misfit 0.0123 at F_r0 = 40.1, F_s0 = 89.7, 2 jobs running, ETA 5m20s (full budget)", or
// nullopt for anything else (another kind, a calibration whose summary does not say its budget).
std::optional<std::string> calibration_line(const nlohmann::json& campaign);

// The table of a calibration's report (its summary JSON).
std::string calibration_text(const nlohmann::json& summary);

}  // namespace rockcal::api
