// A calibration campaign as `rockcal status` shows it: the best misfit so far that its progress
// line (status_text.cpp) adds from the live summary's history, and the table of the final report
// (report_json.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "api/cli/calibration_text.hpp"
#include "api/cli/client_http.hpp"
#include "api/cli/status_text.hpp"
#include "orchestrator/summary_reader.hpp"

namespace rockcal::api {
namespace {

using nlohmann::json;

using summary::at;

std::string num(const json& v, const char* format = "%.4g") {
  return v.is_number() ? summary::printed(v.get<double>(), format) : "-";
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

}  // namespace

std::string best_misfit_text(const json& summary) {
  const json& best = best_so_far(summary);
  if (!best.is_object()) return "";
  return ", best misfit " + num(best["misfit"], "%.3g") + " at F_r0 = " + num(best["fr0"]) +
         ", F_s0 = " + num(best["fs0"]);
}

namespace {

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

// Where the check runs ran when the posterior moved its estimate after them, as "(F_r0 59.58,
// F_s0 39.47)"; empty when they ran at the estimate.
std::string moved_check_point(const json& posterior) {
  const json& p = at(posterior, "checked_at");
  if (at(posterior, "estimate_moved_after_check") != true || !p.is_object()) return "";
  return "(F_r0 " + num(p["fr0"].get<double>(), "%.4g") + ", F_s0 " +
         num(p["fs0"].get<double>(), "%.4g") + ")";
}

// The rock at the estimate: "rock at the estimate (lab units): UCS 105 MPa [98.1, 112], BTS 17.5
// MPa [16.8, 18.2]; E 11.2 GPa (lab 12.3) and nu 0.212 (lab 0.2) from 2 check runs", or "from
// the elastic test (UCT slope 6.1 GPa)" when the stiffness stage measured them. When the estimate
// moved after the check runs (posterior.estimate_moved_after_check), E and nu are the check runs'
// at their own point, which the text names.
std::string rock_text(const json& r, const json& posterior) {
  if (!r.is_object()) return "";
  const bool lab = at(r, "units") == "lab";
  const double mpa = lab ? 1e-6 : 1.0;
  const std::string su = lab ? " MPa" : " Pa";
  auto strength = [&](const char* name, const json& v) {
    return std::string(name) + " " + num(mpa * v["value"].get<double>(), "%.4g") + su + " [" +
           num(mpa * v["interval"][0].get<double>(), "%.4g") + ", " +
           num(mpa * v["interval"][1].get<double>(), "%.4g") + "]";
  };
  std::string out = std::string("rock at the estimate (") + (lab ? "lab" : "model") +
                    " units): " + strength("UCS", r["ucs_pa"]) + ", " +
                    strength("BTS", r["bts_pa"]);
  const json& e = at(r, "youngs_modulus_pa");
  const json& nu = at(r, "poisson_ratio");
  auto measured = [&](const char* name, const json& v, double scale, const char* unit) {
    if (!v.is_object() || !v["value"].is_number()) return std::string(name) + " not measured";
    std::string t = std::string(name) + " " + num(scale * v["value"].get<double>(), "%.3g") + unit;
    if (v["lab"].is_number()) t += " (lab " + num(scale * v["lab"].get<double>(), "%.3g") + ")";
    return t;
  };
  out += "; " + measured("E", e, lab ? 1e-9 : 1.0, lab ? " GPa" : " Pa") + " and " +
         measured("nu", nu, 1.0, "");
  if (at(e, "measure") == "elastic") {
    out += " from the elastic test";
    if (e["runs"].is_number() && e["runs"].get<int>() > 1)
      out += " (mean of " + e["runs"].dump() + " packings)";
    if (e["uct"].is_number())
      out += " (UCT slope " + num((lab ? 1e-9 : 1.0) * e["uct"].get<double>(), "%.3g") +
             (lab ? " GPa" : " Pa") + ")";
  } else if (e.is_object() && e["runs"].is_number()) {
    out += " from " + e["runs"].dump() + " check runs";
    const std::string checked = moved_check_point(posterior);
    if (!checked.empty()) out += " at " + checked;
    // A run that measured E without nu (a result from an engine before the UCT's gauges).
    if (nu.is_object() && nu["value"].is_number() && nu["runs"].is_number() &&
        nu["runs"] != e["runs"])
      out += " (nu from " + nu["runs"].dump() + ")";
  }
  return out + "\n";
}

// The stiffness stage: "stiffness (lab units, elastic test): E 69.1 GPa (target 69) and nu 0.262
// (target 0.26) at K_r 4.2e+04, K_s/K_r 0.46 - <why>".
std::string stiffness_text(const json& st) {
  if (!st.is_object()) return "";
  const json& lab = at(st, "lab");
  const json& e = at(st, "youngs_modulus_pa");
  const json& nu = at(st, "poisson_ratio");
  auto value = [](const json& v, double scale, const char* unit) {
    return v.is_number() ? num(scale * v.get<double>(), "%.3g") + unit
                         : std::string("not measured");
  };
  std::string out =
      std::string("stiffness (") + (lab.is_object() ? "lab" : "model") + " units, elastic test):";
  if (e.is_object()) {
    const json& shown = lab.is_object() ? lab["youngs_modulus_pa"] : e;
    const double scale = lab.is_object() ? 1e-9 : 1.0;
    const char* unit = lab.is_object() ? " GPa" : " Pa";
    out += " E " + value(shown["measured"], scale, unit) + " (target " +
           value(shown["target"], scale, unit) + ")";
  }
  if (nu.is_object()) {
    out += std::string(e.is_object() ? " and" : "") + " nu " + value(nu["measured"], 1.0, "") +
           " (target " + value(nu["target"], 1.0, "") + ")";
  }
  return out + " at K_r " + num(st["kr"].get<double>(), "%.4g") + ", K_s/K_r " +
         num(st["ks_over_kr"].get<double>(), "%.3g") + " - " + value_text(at(st, "why")) + "\n";
}

// The "bayes" strategy's answer: the estimate and the credible intervals of both strengths, the
// predicted loads with their intervals, in the targets' units (lab beside model when given).
std::string posterior_text(const json& p) {
  std::ostringstream out;
  const json& lab = at(p, "lab");
  const bool in_lab = lab.is_object();
  const int pct = int(std::lround(100 * p["level"].get<double>()));
  const json& lu = at(p, "lab_uncertainty");
  out << "posterior from " << p["runs"] << " runs at " << p["points"]
      << " points; targets known to UCT " << num(100 * lu["uct"].get<double>(), "%.3g") << "%, BTT "
      << num(100 * lu["btt"].get<double>(), "%.3g") << "% ("
      << (at(lu, "source") == "request" ? "stated" : "default: not stated in the request") << ")\n";
  char line[256];
  std::snprintf(line, sizeof line, "%-10s%12s  %-24s%s\n", "strength", "estimate",
                (std::to_string(pct) + "% interval").c_str(),
                in_lab ? "lab units (N): estimate, interval" : "");
  out << line;
  for (const char* key : {"fr0", "fs0"}) {
    std::string lab_text;
    if (in_lab) lab_text = num(lab["estimate"][key]) + ", " + range_text(lab[key]);
    std::snprintf(line, sizeof line, "  %-8s%12s  %-24s%s\n",
                  key == std::string("fr0") ? "F_r0" : "F_s0", num(p["estimate"][key]).c_str(),
                  range_text(p[key]).c_str(), lab_text.c_str());
    out << line;
  }
  const std::string unit = in_lab ? " (N)" : "";
  std::snprintf(line, sizeof line, "%-6s%14s%14s  %-26s%s\n", "load", ("target" + unit).c_str(),
                ("predicted" + unit).c_str(),
                (std::to_string(pct) + "% interval of the mean").c_str(), "error");
  out << line;
  for (const char* test : {"uct", "btt"}) {
    const json& t = p[test];
    const json& shown = in_lab && at(t, "lab").is_object() ? t["lab"] : t;
    std::snprintf(line, sizeof line, "  %-4s%14s%14s  %-26s%s\n",
                  test == std::string("uct") ? "UCT" : "BTT", num(shown["target"], "%.6g").c_str(),
                  num(shown["mean"], "%.6g").c_str(), range_text(shown["interval"]).c_str(),
                  (num(100 * t["relative_error"].get<double>(), "%+.2f") + "%").c_str());
    out << line;
  }
  for (const json& t : at(p, "further").is_array() ? p["further"] : json::array()) {
    const json& shown = in_lab && at(t, "lab").is_object() ? t["lab"] : t;
    std::snprintf(line, sizeof line, "  %-4s%14s%14s  %-26s%s  (%s)\n", "more",
                  num(shown["target"], "%.6g").c_str(), num(shown["mean"], "%.6g").c_str(),
                  range_text(shown["interval"]).c_str(),
                  (num(100 * t["relative_error"].get<double>(), "%+.2f") + "%").c_str(),
                  value_text(at(t, "name")).c_str());
    out << line;
  }
  out << "  one packing's scatter: UCT sd " << num(100 * p["uct"]["run_sd"].get<double>(), "%.3g")
      << "%, BTT sd " << num(100 * p["btt"]["run_sd"].get<double>(), "%.3g") << "% (in ln)\n";
  // The check runs against the prediction, with the spread the prediction allows their mean; a
  // test whose check runs gave no peak has nothing to judge.
  std::string checks;
  for (const char* test : {"uct", "btt"}) {
    const json& k = at(p[test], "check");
    if (!k.is_object()) continue;
    checks += std::string(checks.empty() ? "" : "; ") +
              (test == std::string("uct") ? "UCT " : "BTT ") +
              num(100 * k["relative_error"].get<double>(), "%+.2f") + "% of the target, " +
              num(100 * k["relative_to_prediction"].get<double>(), "%+.2f") +
              "% of the prediction (its sd " + num(100 * k["sd"].get<double>(), "%.2g") + "% for " +
              value_text(at(k, "runs")) +
              " packings: " + (k["agrees"] == true ? "agrees" : "DISAGREES") + ")";
  }
  const std::string checked = moved_check_point(p);
  const json& failed = at(p, "check_failed");
  if (failed.is_string() && at(p, "checked_at").is_object()) {
    const json& k = p["checked_at"];
    out << "  check runs at (F_r0 " << num(k["fr0"].get<double>(), "%.4g") << ", F_s0 "
        << num(k["fs0"].get<double>(), "%.4g") << "): no loads (" << failed.get<std::string>()
        << ")\n";
  }
  if (!checks.empty()) {
    out << "  check runs at "
        << (checked.empty() ? "the estimate"
                            : checked +
                                  ", the estimate before them (the estimate moved with "
                                  "them; no run there)")
        << ": " << checks << "\n";
  }
  return out.str();
}

}  // namespace

std::string calibration_text(const json& s) {
  std::ostringstream out;
  out << "verdict: " << value_text(at(s, "verdict")) << " - " << value_text(at(s, "verdict_reason"))
      << "\n";
  out << stiffness_text(at(s, "stiffness"));
  const json& best = at(s, "best");
  const json& posterior = at(s, "posterior");
  if (posterior.is_object()) {
    out << posterior_text(posterior);
    out << rock_text(at(s, "rock_properties"), posterior);
    out << "unique: " << (at(posterior, "unique") == true ? "yes" : "no") << " - "
        << value_text(at(posterior, "why")) << "\n";
    const json& next = at(s, "suggestion");
    if (next.is_object()) {
      out << "next test: " << value_text(at(next, "observable")) << " - "
          << value_text(at(next, "why")) << "\n";
      for (const json& k : at(next, "candidates")) {
        if (!at(k, "expected_shrinkage").is_number()) continue;
        out << "  " << value_text(at(k, "observable")) << ": the long axis "
            << num(100 * k["expected_shrinkage"].get<double>(), "%.0f") << "% shorter\n";
      }
    }
  } else if (best.is_object()) {
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
  if (!posterior.is_object()) out << consistency_text(s);
  out << fidelity_text(at(s, "fidelity"));
  // The same count the progress line showed: the progress model's.
  const json& model = at(s, "progress");
  if (model.is_object()) {
    out << "evaluations: " << summary::budget_count(model, "");
  } else {
    out << "evaluations: " << value_text(at(s, "evaluations"));
  }
  if (at(s, "failed_evaluations").is_number() && s["failed_evaluations"].get<int>() > 0) {
    out << ", " << s["failed_evaluations"].dump() << " failed";
  }
  if (at(s, "realisations").is_number() && s["realisations"].get<int>() > 1) {
    out << ", " << s["realisations"] << " packings each";
  }
  out << ", stopped: " << value_text(at(s, "stop_reason"));
  const json& wall = at(at(s, "pace"), "wall_seconds");
  if (wall.is_number()) out << ", wall time " << duration_text(wall.get<double>());
  out << "\n";
  const json& why = at(at(s, "ensemble"), "why");
  if (why.is_string() && !why.get<std::string>().empty())
    out << "ensemble: " << why.get<std::string>() << "\n";
  return out.str();
}

}  // namespace rockcal::api
