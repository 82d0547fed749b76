// What went wrong in a calibration's runs, as sentences for its verdict: runs that ended without a
// peak (by the limit that ended them, with the fix) and runs that were not quasi-static by their
// own measure (with the fix). Each is empty when no run has the fault.
#pragma once

#include <string>
#include <vector>

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/ledger.hpp"

namespace rockcal::calibration {

// True for a run's (or an evaluation's) error that says it ended without a peak ("no peak: ...").
bool is_no_peak(const std::string& error);

std::string no_peak_text(const std::vector<EvaluationRecord>& history);

// Runs whose result says quasi_static: false (the platen closed the bonds' failure strain in too
// few wave transits, engine/loadtests/loading_speed.hpp). `platen_velocity` is the job template's
// loading.platen_velocity (a number, or "auto").
// The job template's loading.platen_velocity (null when absent).
nlohmann::json platen_velocity_of(const CalibrationCampaign& c);

std::string not_quasi_static_text(const std::vector<EvaluationRecord>& history,
                                  const nlohmann::json& platen_velocity);

}  // namespace rockcal::calibration
