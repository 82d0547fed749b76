// Runs a parsed job and writes everything a run produces into a directory.
#pragma once

#include <atomic>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "engine/spec.hpp"

namespace rockcal {

// Returns the result JSON (also written to dir/result.json). `stop` aborts the run early: then the
// curve is kept and no result.json is written, and the returned JSON has "stop_reason":
// "cancelled".
nlohmann::json run_job(const JobSpec& spec, const std::filesystem::path& dir,
                       const std::atomic<bool>* stop, bool progress_on_stderr);

}  // namespace rockcal
