// A diagnosis's summary as `rockcal diagnose` and `rockcal status` print it: the verdict, the gap
// and the candidates as plain-text tables.
#include "api/cli/diagnosis_text.hpp"

#include <cstdio>
#include <sstream>
#include <string>

#include "orchestrator/summary_reader.hpp"

namespace rockcal::api {
namespace {

using nlohmann::json;
using summary::at;

std::string fmt(const json& v, const char* format = "%.4g") {
  if (!v.is_number()) return v.is_string() ? v.get<std::string>() : "-";
  return summary::printed(v.get<double>(), format);
}

}  // namespace

std::string diagnosis_text(const json& s) {
  std::ostringstream out;
  const json& v = at(s, "verdict");
  const json& p = at(v, "parameter");
  const json& c = at(v, "confidence");
  out << "Verdict: " << fmt(at(v, "label"));
  if (p.is_object()) {
    out << " (" << fmt(at(p, "name")) << " = " << fmt(at(p, "value"));
    const json& span = at(p, "same_model");
    if (span.is_object()) {
      out << ", the same model as any value in [" << fmt(at(span, "from")) << ", "
          << fmt(at(span, "to")) << ")";
    }
    out << ")";
  }
  const json& e = at(v, "evidence");
  if (at(v, "effect").is_string() && at(e, "value").is_number()) {
    out << ", evidence " << fmt(at(e, "value"), "%.2f") << " nats (threshold "
        << fmt(at(e, "threshold"), "%.2f") << ")";
  }
  if (at(v, "gap_closure").is_number()) out << ", G = " << fmt(at(v, "gap_closure"), "%.2f");
  out << ", confidence " << fmt(at(c, "level")) << " (bootstrap "
      << fmt(at(at(c, "bootstrap"), "agreement"), "%.2f") << ", seeds "
      << fmt(at(c, "seeds_agreeing")) << "/" << fmt(at(c, "seeds_informative"))
      << (at(c, "seeds_identical").is_number() && at(c, "seeds_identical").get<int>() > 0
              ? ", " + fmt(at(c, "seeds_identical")) + " identical to the nominal runs"
              : "")
      << ")\n  " << fmt(at(v, "reason")) << "\n  F_r0 = " << fmt(at(v, "fr0"))
      << ", F_s0 = " << fmt(at(v, "fs0")) << "\n\n";
  char line[256];
  std::snprintf(line, sizeof line, "  %-22s %10s %10s\n", "rms ln(sim/lab)", "before", "after");
  out << line;
  for (const char* role : {"calibration", "held_out"}) {
    const json& g = at(at(v, "gap"), role);
    std::snprintf(line, sizeof line, "  %-22s %10s %10s\n", role,
                  fmt(at(g, "before"), "%.4f").c_str(), fmt(at(g, "after"), "%.4f").c_str());
    out << line;
  }
  const json& u = at(v, "runner_up");
  if (u.is_object()) {
    out << "Runner-up: " << fmt(at(u, "effect")) << ", evidence " << fmt(at(u, "evidence"), "%.2f")
        << " nats, G = " << fmt(at(u, "gap_closure"), "%.2f") << " (" << fmt(at(u, "basis"))
        << ")\n";
  }
  if (at(at(s, "screen"), "reason").is_string()) {
    out << "Screen: " << fmt(at(at(s, "screen"), "reason")) << "\n";
  }
  if (at(at(s, "next_test"), "reason").is_string()) {
    out << "Next test: " << fmt(at(at(s, "next_test"), "reason")) << "\n";
  }
  out << "\nWhere the gap lies (base model; * = beyond budget + lab uncertainty + the fit's "
         "spread):\n";
  std::snprintf(line, sizeof line, "  %-14s %-9s %-15s %-11s %12s %12s %9s %8s %8s %8s %9s\n",
                "observation", "test", "observable", "role", "lab", "base sim", "ln ratio",
                "budget", "lab unc", "fit", "after");
  out << line;
  for (const json& o : at(s, "observations")) {
    const json& b = at(o, "base");
    std::snprintf(
        line, sizeof line, "  %-14s %-9s %-15s %-11s %12s %12s %8s%s %8s %8s %8s %9s\n",
        fmt(at(o, "id")).c_str(), fmt(at(o, "test")).c_str(), fmt(at(o, "observable")).c_str(),
        fmt(at(o, "role")).c_str(), fmt(at(o, "lab")).c_str(), fmt(at(b, "sim")).c_str(),
        fmt(at(b, "residual"), "%+.4f").c_str(), at(b, "significant") == true ? "*" : " ",
        fmt(at(o, "budget"), "%.4f").c_str(), fmt(at(o, "lab_uncertainty"), "%.4f").c_str(),
        fmt(at(b, "fit_spread"), "%.4f").c_str(),
        fmt(at(at(o, "verdict"), "residual"), "%+.4f").c_str());
    out << line;
  }
  const json& runs = at(s, "runs");
  if (at(runs, "failed_values").is_number() && runs["failed_values"].get<int>() > 0) {
    out << "  " << fmt(at(runs, "failed_values"))
        << " values missing from the grids (first: " << fmt(at(runs, "first_error")) << ")\n";
  }
  const json& candidates = at(s, "candidates");
  if (candidates.is_array() && !candidates.empty()) {
    const json& bounds = at(at(candidates[0], "fit"), "on_bounds");
    if (bounds.is_array() && !bounds.empty()) {
      out << "  The base model's fit lies on the bounds (";
      for (std::size_t k = 0; k < bounds.size(); ++k) out << (k ? ", " : "") << fmt(bounds[k]);
      out << "): the data want strengths outside them (widen \"bounds\"; or the lab's UCT/BTT "
             "ratio is out of the base model's reach), or do not depend on that strength there\n";
    }
  }
  out << "\nCandidates (ranked by held-out evidence over the base model, nats):\n";
  std::snprintf(line, sizeof line, "  %4s %-22s %-12s %-8s %9s %8s %-10s %s\n", "rank", "effect",
                "identifiable", "fits cal", "evidence", "G", "basis", "fitted parameter");
  out << line;
  const json& missing = at(at(s, "gap"), "closure_missing");
  if (missing.is_string()) out << "  No gap closure to show: " << fmt(missing) << ".\n";
  std::vector<json> ranked;
  for (const json& k : at(s, "candidates")) {
    if (k["effect"].is_string()) ranked.push_back(k);
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const json& a, const json& b) {
    return a["rank"].get<int>() < b["rank"].get<int>();
  });
  for (const json& k : ranked) {
    const json& kp = at(k, "parameter");
    const std::string param =
        kp.is_object() ? fmt(at(kp, "name")) + " = " + fmt(at(kp, "value")) : "";
    auto yes_no = [&](const char* key) {
      return at(k, key).is_boolean() ? (k[key].get<bool>() ? "yes" : "no") : "-";
    };
    std::snprintf(line, sizeof line, "  %4s %-22s %-12s %-8s %9s %8s %-10s %s\n",
                  fmt(at(k, "rank")).c_str(), k["effect"].get<std::string>().c_str(),
                  yes_no("identifiable"), yes_no("fits_calibration"),
                  fmt(at(at(k, "evidence"), "value"), "%.2f").c_str(),
                  fmt(at(at(k, "gap_closure"), "value"), "%.3f").c_str(),
                  fmt(at(at(k, "gap_closure"), "basis")).c_str(), param.c_str());
    out << line;
  }
  const json& r = at(s, "ratio");
  if (r.is_object()) {
    out << "\nUCT/BTT ratio: lab " << fmt(at(r, "lab"), "%.3g") << ", the base model reaches "
        << fmt(at(r, "min"), "%.3g") << " to " << fmt(at(r, "max"), "%.3g") << " ("
        << (at(r, "inside") == true ? "inside" : "outside") << ")\n";
  }
  return out.str();
}

}  // namespace rockcal::api
