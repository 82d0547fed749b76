// Files a run writes: result.json (last, atomically), curve.csv, breaks.csv, progress.json, VTK.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "engine/loadtests/result.hpp"

namespace rockcal {

struct Simulation;

nlohmann::json result_to_json(const JobSpec& spec, const TestResult& r, int ranks);

// Writes `text` to `path` through a temporary file and a rename, so readers never see half a file.
void write_atomically(const std::filesystem::path& path, const std::string& text);

void write_curve_csv(const std::filesystem::path& path, const std::vector<CurvePoint>& curve);
void write_breaks_csv(const std::filesystem::path& path, const std::vector<BreakEvent>& breaks);
nlohmann::json progress_to_json(const Progress& p);

// ParaView files: particles_NNNN.vtu (radius, velocity, id) and breaks.vtu (where bonds broke).
void write_particles_vtu(const std::filesystem::path& path, const Simulation& sim);
void write_breaks_vtu(const std::filesystem::path& path, const std::vector<BreakEvent>& breaks);

}  // namespace rockcal
