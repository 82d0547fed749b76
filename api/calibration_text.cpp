// A calibration campaign as `rockcal status` shows it: the progress line from the live summary
// (orchestrator/calibration/calibration_kind.cpp: history, max_evaluations, scatter_runs, pace)
// and the table of the final report (report_json.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "api/client_http.hpp"
#include "api/status_text.hpp"

namespace rockcal::api {
namespace {

using nlohmann::json;

const json& at(const json& j, const char* key) {
  static const json null;
  return j.is_object() && j.contains(key) ? j[key] : null;
}

std::string num(const json& v, const char* format = "%.4g") {
  if (!v.is_number()) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, v.get<double>());
  return buffer;
}

std::string num(double v, const char* format = "%.4g") {
  return num(json(v), format);
}

// The successful evaluation of lowest misfit in a summary's history, or null.
const json& best_so_far(const json& summary) {
  static const json null;
  const json* best = &null;
  for (const json& row : at(summary, "history")) {
    if (at(row, "ok") != true || !at(row, "misfit").is_number()) continue;
    if (best->is_null() || row["misfit"].get<double>() < (*best)["misfit"].get<double>()) {
      best = &row;
    }
  }
  return *best;
}

// Seconds for the evaluations still possible: the search's remaining budget plus the seed
// re-runs of the best point, at the measured pace. Null until one evaluation has run (the pace is
// unknown) and once nothing is left.
// The whole budget: the search's and the consistent-set trace's after it.
int budget_of(const json& summary) {
  const json& trace = at(summary, "consistency_evaluations");
  return at(summary, "max_evaluations").get<int>() + (trace.is_number() ? trace.get<int>() : 0);
}

std::optional<double> eta_seconds(const json& summary) {
  const json& per = at(at(summary, "pace"), "seconds_per_evaluation");
  if (!per.is_number()) return std::nullopt;
  const int left = std::max(0, budget_of(summary) - at(summary, "evaluations").get<int>()) +
                   at(summary, "scatter_runs").get<int>();
  if (left == 0) return std::nullopt;
  // At least a second: a running campaign never shows "ETA 0s".
  return std::max(1.0, std::ceil(left * per.get<double>()));
}

bool is_live_calibration(const json& campaign) {
  const json& s = at(campaign, "summary");
  return at(campaign, "kind") == "calibration" && at(s, "max_evaluations").is_number() &&
         at(s, "evaluations").is_number() && at(s, "scatter_runs").is_number();
}

std::string calibration_line(const json& c) {
  const json& s = c["summary"];
  const std::string state = c["state"].get<std::string>();
  std::ostringstream out;
  out << "campaign " << c["id"] << " " << state << ": " << s["evaluations"] << " of "
      << budget_of(s) << " evaluations done";
  if (s["scatter_runs"].get<int>() > 0) out << " (+" << s["scatter_runs"] << " seed re-runs)";
  const json& best = best_so_far(s);
  if (best.is_object()) {
    out << ", best misfit " << num(best["misfit"], "%.3g") << " at F_r0 = " << num(best["fr0"])
        << ", F_s0 = " << num(best["fs0"]);
  }
  const json& running = at(c["progress"], "running");
  out << ", " << running << (running == 1 ? " job" : " jobs") << " running";
  if (state == "running" || state == "queued") {
    if (const auto eta = eta_seconds(s)) {
      out << ", ETA " << duration_text(*eta) << " (full budget)";
    } else if (at(at(s, "pace"), "seconds_per_evaluation").is_number()) {
      out << ", finishing";
    } else {
      out << ", ETA unknown";
    }
  }
  return out.str();
}

// "+1.25% ± 0.40%": the relative error and, for an ensemble mean, its standard error.
std::string error_text(const json& test) {
  std::string out = num(100 * at(test, "relative_error").get<double>(), "%+.2f") + "%";
  const json& se = at(test, "se");
  if (se.is_number() && at(test, "target").is_number()) {
    out += " ± " + num(100 * se.get<double>() / test["target"].get<double>(), "%.2f") + "%";
  }
  return out;
}

// One load row: target, simulated (± standard error, in the row's units) and error. `shown` is
// the test in the units shown (lab or model), `model` the same test in model units (its se, n).
std::string load_row(const char* name, const json& shown, const json& model) {
  std::string simulated = num(shown["peak_load"], "%.6g");
  const json& se = at(model, "se");
  if (se.is_number()) {
    // The standard error scales with the load from model to lab units.
    const double factor = shown["peak_load"].get<double>() / model["peak_load"].get<double>();
    simulated += " ± " + num(se.get<double>() * factor, "%.3g");
  }
  char head[64];
  std::snprintf(head, sizeof head, "  %-4s %10s   ", name, num(shown["target"], "%.6g").c_str());
  std::string out =
      head + padded(simulated, 20) +
      error_text(
          {{"relative_error", shown["relative_error"]}, {"se", se}, {"target", model["target"]}});
  if (at(model, "n").is_number() && model["n"].get<int>() > 1) {
    out += "  (mean of " + model["n"].dump() + ")";
  }
  return out + "\n";
}

std::string range_text(const json& range) {
  if (!range.is_array() || range.size() != 2) return "-";
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on "[" + std::string.
  std::string text = "[";
  return text.append(num(range[0])).append(", ").append(num(range[1])).append("]");
}

std::string value_text(const json& v) {
  return v.is_number() ? num(v) : v.is_string() ? v.get<std::string>() : v.dump();
}

// The consistent set, the unique flag and the suggestion of the report, when present.
std::string consistency_text(const json& s) {
  std::ostringstream out;
  const json& set = at(s, "consistent");
  if (set.is_object()) {
    out << "consistent with the targets: F_r0 " << range_text(at(set, "fr0")) << ", F_s0 "
        << range_text(at(set, "fs0")) << ", ratio " << range_text(at(set, "ratio"));
    if (at(set, "points").is_array()) out << " (" << set["points"].size() << " points)";
    out << "\n";
  }
  if (at(s, "unique").is_boolean()) {
    out << "unique: " << (s["unique"].get<bool>() ? "yes" : "no") << "\n";
  }
  const json& g = at(s, "suggestion");
  if (g.is_object()) {
    out << "suggestion: measure " << value_text(at(g, "observable"));
    if (at(g, "values").is_array() && !g["values"].empty()) {
      std::string values;
      for (const json& v : g["values"]) values += (values.empty() ? "" : ", ") + value_text(v);
      out << " (" << values << ")";
    }
    if (at(g, "why").is_string()) out << ": " << g["why"].get<std::string>();
    out << "\n";
  }
  return out.str();
}

// The best point's loads over other packings (the "seeds" of a request): the spread a reader
// needs beside a single run's error.
std::string scatter_text(const json& scatter) {
  std::string parts;
  for (const char* test : {"uct", "btt"}) {
    const json& t = at(scatter, test);
    if (!at(t, "runs").is_number() || t["runs"].get<int>() < 2) continue;
    parts += std::string(parts.empty() ? "" : ", ") + (test == std::string("uct") ? "UCT" : "BTT") +
             " cv " + num(100 * t["cv"].get<double>(), "%.2f") + "% over " + t["runs"].dump() +
             " packings";
  }
  return parts.empty() ? "" : "  seed scatter of the best point: " + parts + "\n";
}

// The fine specimen's steps of a multi-fidelity campaign: the answer is the last of them, the
// "best bond strengths" above are the coarse search's.
std::string fidelity_text(const json& f) {
  if (!f.is_object() || !f["steps"].is_array() || f["steps"].empty()) return "";
  std::ostringstream out;
  out << "fine specimen (" << f["steps"].size() << " corrections, "
      << (f["met"].get<bool>() ? "met" : "not met")
      << "; the strengths above are the coarse search's):\n";
  for (const json& st : f["steps"]) {
    out << "  F_r0 = " << num(st["fr0"]) << ", F_s0 = " << num(st["fs0"]);
    if (st.contains("uct")) {
      out << ": UCT " << num(100 * st["uct"]["relative_error"].get<double>(), "%+.2f") << "%, BTT "
          << num(100 * st["btt"]["relative_error"].get<double>(), "%+.2f") << "%";
    } else {
      out << ": " << st["error"].get<std::string>();
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace

std::string calibration_text(const json& s) {
  std::ostringstream out;
  out << "verdict: " << value_text(at(s, "verdict")) << " - " << value_text(at(s, "verdict_reason"))
      << "\n";
  const json& best = at(s, "best");
  if (best.is_object()) {
    const json& lab = at(best, "lab");
    const bool in_lab = lab.is_object();
    char line[256];
    std::snprintf(line, sizeof line, "%-20s%12s%s\n", "best bond strengths", "model units",
                  in_lab ? "   lab units (N)" : "");
    out << line;
    for (const char* key : {"fr0", "fs0"}) {
      const std::string lab_value = in_lab ? num(lab[key]) : "";
      std::snprintf(line, sizeof line, "  %-18s%12s%*s\n",
                    key == std::string("fr0") ? "F_r0" : "F_s0", num(best[key]).c_str(),
                    in_lab ? 16 : 0, lab_value.c_str());
      out << line;
    }
    // Loads in the units the targets were given in.
    const std::string unit = in_lab ? " (N)" : "";
    std::snprintf(line, sizeof line, "%-7s%10s   ", "load", ("target" + unit).c_str());
    out << line << padded("simulated" + unit, 20) << "error\n";
    out << load_row("UCT", in_lab ? lab["uct"] : best["uct"], best["uct"]);
    out << load_row("BTT", in_lab ? lab["btt"] : best["btt"], best["btt"]);
    out << scatter_text(at(s, "scatter"));
    out << "  best misfit " << num(best["misfit"], "%.3g") << " at evaluation "
        << value_text(at(best, "evaluation")) << "\n";
  }
  out << consistency_text(s);
  out << fidelity_text(at(s, "fidelity"));
  // The same budget the progress line counted down: the search's and the valley trace's.
  const json& trace = at(s, "consistency_evaluations");
  const bool traced =
      at(s, "max_evaluations").is_number() && trace.is_number() && trace.get<int>() > 0;
  out << "evaluations: " << value_text(at(s, "evaluations")) << " of "
      << (traced ? std::to_string(budget_of(s)) : value_text(at(s, "max_evaluations")));
  std::vector<std::string> notes;
  if (at(s, "failed_evaluations").is_number() && s["failed_evaluations"].get<int>() > 0) {
    notes.push_back(s["failed_evaluations"].dump() + " failed");
  }
  if (traced) {
    notes.push_back("budget: search " + s["max_evaluations"].dump() + ", valley trace " +
                    trace.dump());
  }
  for (std::size_t k = 0; k < notes.size(); ++k) out << (k ? "; " : " (") << notes[k];
  if (!notes.empty()) out << ")";
  if (at(s, "realisations").is_number() && s["realisations"].get<int>() > 1) {
    out << ", " << s["realisations"] << " packings each";
  }
  out << ", stopped: " << value_text(at(s, "stop_reason"));
  const json& wall = at(at(s, "pace"), "wall_seconds");
  if (wall.is_number()) out << ", wall time " << duration_text(wall.get<double>());
  out << "\n";
  const json& why = at(at(s, "ensemble"), "why");
  if (why.is_string()) out << "ensemble: " << why.get<std::string>() << "\n";
  return out.str();
}

std::string progress_line(const json& campaign) {
  return is_live_calibration(campaign) ? calibration_line(campaign) : status_line(campaign);
}

}  // namespace rockcal::api
