// Runs a parsed job and writes everything a run produces into a directory.
#pragma once

#include <mpi.h>

#include <atomic>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "engine/spec.hpp"

namespace rockcal {

// Returns the result JSON (rank 0 also writes it to dir/result.json, last and atomically). `stop`
// aborts the run early: then the curve is kept, no result.json is written, and the returned JSON
// has "stop_reason": "cancelled". With `comm` of several ranks the specimen is decomposed.
nlohmann::json run_job(const JobSpec& spec, const std::filesystem::path& dir,
                       const std::atomic<bool>* stop, bool progress_on_stderr,
                       MPI_Comm comm = MPI_COMM_NULL);

}  // namespace rockcal
