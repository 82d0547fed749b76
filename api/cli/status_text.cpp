// The summary `rockcal status` prints when a campaign has ended, by kind, and the pacing of its
// progress lines in a log.
#include "api/cli/status_text.hpp"

#include <cmath>
#include <sstream>

#include "api/cli/calibration_text.hpp"
#include "api/cli/client.hpp"
#include "api/cli/client_http.hpp"
#include "api/cli/diagnosis_text.hpp"
#include "orchestrator/summary_reader.hpp"

namespace rockcal::api {
namespace {

using nlohmann::json;
using summary::at;

// A campaign without a driver report (a sweep): what its jobs did, and where the numbers are.
std::string jobs_text(const json& c) {
  const json& p = c["progress"];
  std::ostringstream out;
  out << c["kind"].get<std::string>() << " " << c["id"] << " " << c["state"].get<std::string>()
      << ": " << p["total"] << " jobs, " << p["succeeded"] << " succeeded";
  if (p["cached"].get<std::int64_t>() > 0) out << " (" << p["cached"] << " from the cache)";
  out << ", " << p["failed"] << " failed";
  if (p["cancelled"].get<std::int64_t>() > 0) out << ", " << p["cancelled"] << " cancelled";
  out << "\nresults: rockcal results " << c["id"] << " (--csv for one row per job)\n";
  return out.str();
}

// A driver's phase while it runs (a diagnosis): "  [2/4 budget]".
std::string phase_text(const json& c) {
  const json& s = c.contains("summary") ? c["summary"] : json();
  if (!s.is_object() || !s.contains("phase") || !s["phase"].is_string()) return "";
  return "  [" + s.value("step", json()).dump() + "/" + s.value("steps", json()).dump() + " " +
         s["phase"].get<std::string>() + "]";
}

}  // namespace

std::string progress_line(const json& c) {
  const json& s = at(c, "summary");
  const json& model = at(s, "progress");
  if (!at(model, "budget").is_number() || !at(model, "unit").is_string()) {
    return status_line(c) + phase_text(c);
  }
  const std::string state = c["state"].get<std::string>();
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on " " + std::string.
  std::string count = " ";
  count += model["unit"].get<std::string>();
  count += " done";
  std::ostringstream out;
  out << "campaign " << c["id"] << " " << state << ": " << summary::budget_count(model, count);
  if (at(c, "kind") == "calibration") out << best_misfit_text(s);
  const json& running = at(c["progress"], "running");
  out << ", " << running << (running == 1 ? " job" : " jobs") << " running";
  if (state == "running" || state == "queued") {
    const json& eta = at(model, "eta_seconds");
    if (eta.is_number()) {
      out << ", ETA " << duration_text(eta.get<double>()) << " (full budget)";
    } else if (at(model, "left") == 0) {
      out << ", finishing";
    } else {
      out << ", ETA unknown";
    }
  }
  return out.str() + phase_text(c);
}

std::string summary_text(const json& c) {
  const json& s = c.contains("summary") ? c["summary"] : json();
  const std::string kind = c["kind"].get<std::string>();
  const std::string header = kind + " " + c["id"].dump() + " \"" + c["name"].get<std::string>() +
                             "\" " + c["state"].get<std::string>() + "\n";
  if (s.is_object() && s.contains("error") && s["error"].is_string()) {
    return header + "the driver failed: " + s["error"].get<std::string>() + "\n";
  }
  if (kind == "calibration" && s.is_object() && s.contains("verdict")) {
    return header + calibration_text(s);
  }
  if (kind == "diagnosis" && s.is_object() && s.contains("verdict")) {
    return header + diagnosis_text(s);
  }
  return jobs_text(c);
}

std::string duration_text(double seconds) {
  long s = std::lround(seconds);
  std::ostringstream out;
  if (s >= 3600) out << s / 3600 << "h";
  if (s >= 60) out << (s / 60) % 60 << "m";
  out << s % 60 << "s";
  return out.str();
}

bool LinePacer::due(const std::string& line, Clock::time_point now) {
  if (line == last_ || (printed_at_ && now - *printed_at_ < interval_)) return false;
  last_ = line;
  printed_at_ = now;
  return true;
}

}  // namespace rockcal::api
