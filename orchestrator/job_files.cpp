#include "orchestrator/job_files.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace rockcal::orch {
namespace fs = std::filesystem;
using nlohmann::json;

fs::path job_dir(const fs::path& jobs_dir, std::int64_t job_id) {
  if (job_id <= 0) throw std::invalid_argument("job id must be positive");
  return jobs_dir / std::to_string(job_id);
}

fs::path prepare_job_dir(const fs::path& jobs_dir, const db::JobRow& job) {
  fs::path dir = job_dir(jobs_dir, job.id);
  fs::create_directories(dir);
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename() != "log") fs::remove_all(entry.path());
  }
  {
    std::ofstream out(dir / "job.json.tmp");
    out << json::parse(job.spec).dump(2) << "\n";
    if (!out) throw std::runtime_error("cannot write " + (dir / "job.json").string());
  }
  fs::rename(dir / "job.json.tmp", dir / "job.json");
  std::ofstream log(dir / "log", std::ios::app);
  log << "=== rockcal: attempt " << job.attempts << " of job " << job.id << " ===\n";
  return dir;
}

JobOutputs job_outputs(const fs::path& dir) {
  JobOutputs out;
  std::error_code ec;
  out.breaks_csv = fs::is_regular_file(dir / "breaks.csv", ec);
  for (const auto& entry : fs::directory_iterator(dir / "vtk", ec)) {
    const fs::path name = entry.path().filename();
    if (entry.is_regular_file() && (name.extension() == ".vtu" || name.extension() == ".pvd"))
      out.vtk.push_back(name.string());
  }
  std::sort(out.vtk.begin(), out.vtk.end());
  return out;
}

std::optional<std::string> read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

namespace {

std::optional<double> number_or_null(const json& j, const char* key) {
  auto it = j.find(key);
  if (it == j.end() || !it->is_number()) return std::nullopt;
  return it->get<double>();
}

}  // namespace

std::optional<std::string> no_peak_reason(const json& result) {
  if (!result.is_object()) return std::nullopt;
  auto reached = result.find("peak_reached");
  if (reached == result.end() || !reached->is_boolean() || reached->get<bool>()) {
    return std::nullopt;
  }
  auto why = result.find("no_peak_reason");
  if (why != result.end() && why->is_string() && !why->get<std::string>().empty()) {
    return why->get<std::string>();
  }
  auto stop = result.find("stop_reason");
  return "the run stopped (" +
         (stop != result.end() && stop->is_string() ? stop->get<std::string>() : "?") +
         ") before a peak";
}

db::ResultRow read_result(const fs::path& dir, const db::JobRow& job) {
  auto text = read_text(dir / "result.json");
  if (!text) throw std::runtime_error("the run wrote no result.json");
  json j = json::parse(*text, nullptr, false);
  if (!j.is_object()) throw std::runtime_error("result.json is not a JSON object");
  db::ResultRow r;
  r.hash = job.hash;
  r.job_id = job.id;
  r.test = job.test;
  r.fr0 = job.fr0;
  r.fs0 = job.fs0;
  r.no_peak = no_peak_reason(j);
  if (!r.no_peak) {
    r.peak_load = number_or_null(j, "peak_load");
    r.strength = number_or_null(j, "strength");
    r.youngs_modulus = number_or_null(j, "youngs_modulus");
    r.poisson_ratio = number_or_null(j, "poisson_ratio");
  }
  if (auto p = number_or_null(j, "particles")) r.particles = static_cast<std::int64_t>(*p);
  r.wall_seconds = number_or_null(j, "wall_seconds");
  auto version = j.find("engine_version");
  r.engine_version = version != j.end() && version->is_string() ? version->get<std::string>() : "";
  r.result = j.dump();
  r.curve = read_text(dir / "curve.csv");
  return r;
}

std::optional<double> read_progress(const fs::path& dir) {
  auto text = read_text(dir / "progress.json");
  if (!text) return std::nullopt;
  json j = json::parse(*text, nullptr, false);
  if (!j.is_object()) return std::nullopt;  // caught mid-write by a non-atomic writer: skip
  auto f = number_or_null(j, "fraction");
  if (!f) return std::nullopt;
  return std::clamp(*f, 0.0, 1.0);
}

std::string tail_file(const fs::path& file, std::size_t max_lines, std::size_t max_bytes) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) return "";
  auto size = static_cast<std::size_t>(in.tellg());
  std::size_t start = size > max_bytes ? size - max_bytes : 0;
  in.seekg(static_cast<std::streamoff>(start));
  std::string text(size - start, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  std::size_t pos = text.size();
  if (pos > 0 && text[pos - 1] == '\n') --pos;
  for (std::size_t lines = 0; pos > 0; --pos) {
    if (text[pos - 1] == '\n' && ++lines == max_lines) break;
  }
  return text.substr(pos);
}

}  // namespace rockcal::orch
