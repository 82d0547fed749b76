// Files a run writes: result.json (last, atomically), curve.csv, breaks.csv, progress.json, VTK.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

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

// ParaView files: particles_NNNN.vtu (radius, velocity, id; the frame's time, step, load and
// displacement as field data), their series particles.pvd (time as the timestep, with step, load
// and displacement per frame) and breaks.vtu (where bonds broke).
void write_particles_vtu(const std::filesystem::path& path, const Simulation& sim,
                         const Frame& frame);
// particles_NNNN.vtu, or particles_NNNN_rK.vtu (rank K's part) when decomposed.
std::string particles_vtu_name(int frame, int rank, int ranks);
void write_vtk_series(const std::filesystem::path& path, const std::vector<Frame>& frames,
                      int ranks);
void write_breaks_vtu(const std::filesystem::path& path, const std::vector<BreakEvent>& breaks);

}  // namespace rockcal
