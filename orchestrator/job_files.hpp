// The files of one job: <jobs dir>/<job id>/{job.json, result.json, curve.csv, progress.json,
// log}. Paths come from the numeric job id only, never from a request.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "db/records.hpp"

namespace rockcal::orch {

// `jobs_dir` holds a directory per job (by default <data>/jobs).
std::filesystem::path job_dir(const std::filesystem::path& jobs_dir, std::int64_t job_id);

// Clears what an earlier attempt left (except the log, which keeps every attempt) and writes
// job.json. Returns the directory.
std::filesystem::path prepare_job_dir(const std::filesystem::path& jobs_dir, const db::JobRow& job);

// Why a finished run's result.json counts as a run without a peak, or nullopt when it does not:
// it says "peak_reached": false (its "no_peak_reason", else its stop reason). The largest load such
// a run saw is no result. (The engine writes peak_reached for the loading tests only: the elastic
// test has no peak to reach.)
std::optional<std::string> no_peak_reason(const nlohmann::json& result);

// Reads result.json and curve.csv of a finished run into a result row for `job`; a run without a
// peak gets `no_peak` and no values. Throws std::runtime_error when result.json is missing or
// malformed.
db::ResultRow read_result(const std::filesystem::path& dir, const db::JobRow& job);

// The run's progress fraction (0..1) from progress.json, if it has written one.
std::optional<double> read_progress(const std::filesystem::path& dir);

// What a finished run left in its directory `dir` for a reader to download: breaks.csv, and the
// VTK snapshots (vtk/: the series particles.pvd, particles_NNNN[_rK].vtu, breaks.vtu) by file
// name, sorted.
struct JobOutputs {
  bool breaks_csv = false;
  std::vector<std::string> vtk;
};
JobOutputs job_outputs(const std::filesystem::path& dir);

// The last `max_lines` lines (at most `max_bytes`) of a text file; "" if it does not exist.
std::string tail_file(const std::filesystem::path& file, std::size_t max_lines,
                      std::size_t max_bytes);

// Whole small file, or nullopt if missing.
std::optional<std::string> read_text(const std::filesystem::path& file);

}  // namespace rockcal::orch
