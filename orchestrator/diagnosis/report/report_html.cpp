// The HTML page of a diagnosis: made from the stored summary alone (to_json), so the service can
// render it for any finished campaign and `rockcal diagnose` can fetch and save it.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "orchestrator/diagnosis/report/report.hpp"
#include "orchestrator/diagnosis/report/svg.hpp"
#include "orchestrator/summary_reader.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

const char* const kPalette[] = {"#555",    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22"};

double number(const json& v) {
  return v.is_number() ? v.get<double>() : NAN;
}

using summary::at;

std::string show(const json& v, const char* format = "%.4g") {
  if (v.is_number()) return summary::printed(v.get<double>(), format);
  if (v.is_string()) return escape_html(v.get<std::string>());
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  return "&ndash;";
}

std::string percent(const json& v) {
  return v.is_number() ? show(json(100 * v.get<double>()), "%.1f%%") : "&ndash;";
}

std::string effect_name(const json& candidate) {
  return candidate["effect"].is_string() ? candidate["effect"].get<std::string>() : "base";
}

std::string conditions_text(const json& c) {
  std::string out;
  for (auto it = c.begin(); it != c.end(); ++it) {
    out += (out.empty() ? "" : ", ") + escape_html(it.key()) + " " + show(it.value());
  }
  return out;
}

std::string verdict_section(const json& s) {
  const json& v = at(s, "verdict");
  const json& p = at(v, "parameter");
  std::string out = "<section class=\"verdict\"><h2>Verdict: " + show(at(v, "label")) + "</h2>\n";
  out += "<p>" + show(at(v, "reason")) + "</p>\n<table>";
  if (p.is_object()) {
    const json& span = at(p, "same_model");
    out +=
        "<tr><th>fitted " + show(at(p, "name")) + "</th><td>" + show(at(p, "value")) + " " +
        show(at(p, "unit")) + " (s = " + show(at(p, "s"), "%.2f") + ")" +
        (span.is_object() ? "; the same model as any value in [" + show(at(span, "from"), "%.4g") +
                                ", " + show(at(span, "to"), "%.4g") + ")"
                          : std::string()) +
        "</td></tr>";
  }
  out += "<tr><th>F_r0, F_s0</th><td>" + show(at(v, "fr0")) + ", " + show(at(v, "fs0")) +
         " N</td></tr>";
  const json& e = at(v, "evidence");
  out += "<tr><th>evidence (held out)</th><td>" +
         (at(e, "effect").is_string()
              ? show(at(e, "effect")) + ": " + show(at(e, "value"), "%.2f") + " nats over the base"
              : std::string("no contender")) +
         "; threshold " + show(at(e, "threshold"), "%.2f") + " nats</td></tr>";
  out += "<tr><th>gap closure G</th><td>" + show(at(v, "gap_closure"), "%.2f") + "</td></tr>";
  out += "<tr><th>gap closure beyond noise</th><td>" +
         show(at(v, "gap_closure_beyond_noise"), "%.2f") + "</td></tr>";
  const json& gap = at(v, "gap");
  for (const char* role : {"calibration", "held_out"}) {
    out += std::string("<tr><th>rms ") + role + " before &rarr; after</th><td>" +
           show(at(at(gap, role), "before"), "%.4f") + " &rarr; " +
           show(at(at(gap, role), "after"), "%.4f") + "</td></tr>";
  }
  const json& u = at(v, "runner_up");
  if (u.is_object()) {
    out += "<tr><th>runner-up</th><td>" + show(at(u, "effect")) + ", evidence " +
           show(at(u, "evidence"), "%.2f") + " nats, G = " + show(at(u, "gap_closure"), "%.2f") +
           " (" + show(at(u, "basis")) + ")</td></tr>";
  }
  const json& c = at(v, "confidence");
  out += "<tr><th>confidence</th><td>" + show(at(c, "level")) + ": bootstrap agreement " +
         percent(at(at(c, "bootstrap"), "agreement")) + " of " +
         show(at(at(c, "bootstrap"), "replicates")) + " replicates; " +
         show(at(c, "seeds_agreeing")) + " of " + show(at(c, "seeds_informative")) +
         " replicate seeds agree" +
         (at(c, "seeds_identical").is_number() && at(c, "seeds_identical").get<int>() > 0
              ? " (" + show(at(c, "seeds_identical")) +
                    " more re-ran identically to the nominal runs and are not counted)"
              : "") +
         "</td></tr>";
  out += "</table>\n<p class=\"note\">" + show(at(c, "method")) + "</p></section>\n";
  return out;
}

std::string gap_section(const json& s) {
  const json& g = at(s, "gap");
  std::string out =
      "<h2>Where the gap lies</h2>\n<p>Base model (bond strengths only), real runs "
      "at its fitted point: rms ln(sim/lab) calibration " +
      show(at(at(g, "rms"), "calibration"), "%.4f") + ", held out " +
      show(at(at(g, "rms"), "held_out"), "%.4f") + "; combined budget " +
      show(at(at(g, "combined_budget"), "held_out"), "%.4f") +
      " (held out). Held-out residuals in budgets (rms of each over its own budget and lab "
      "uncertainty; a gap above 1): " +
      show(at(g, "held_out_budgets"), "%.2f") +
      ". A residual beyond budget + lab uncertainty is marked.</p>\n";
  const json& candidates = at(s, "candidates");
  const json& bounds = candidates.is_array() && !candidates.empty()
                           ? at(at(candidates[0], "fit"), "on_bounds")
                           : candidates;
  if (bounds.is_array() && !bounds.empty()) {
    std::string which;
    for (const json& b : bounds) which += (which.empty() ? "" : ", ") + show(b);
    out += "<p class=\"note\">The base model's fit lies on the bounds (" + which +
           "): the calibration observations want bond strengths outside them (widen "
           "<code>bounds</code>; a lab UCT/BTT ratio the base model cannot reach, see below, is "
           "itself a gap), or do not depend on that strength there.</p>\n";
  }
  out +=
      "<table><tr><th>observation</th><th>test</th><th>observable</th><th>conditions</th>"
      "<th>role</th><th>lab</th><th>base sim</th><th>ln(sim/lab)</th><th>budget</th>"
      "<th>lab unc.</th><th>after</th></tr>\n";
  for (const json& o : at(s, "observations")) {
    const json& base = at(o, "base");
    const bool gap = at(base, "significant").is_boolean() && base["significant"].get<bool>();
    out += std::string("<tr") + (gap ? " class=\"gap\"" : "") + "><td>" + show(at(o, "id")) +
           "</td><td>" + show(at(o, "test")) + "</td><td>" + show(at(o, "observable")) +
           "</td><td>" + conditions_text(at(o, "conditions")) + "</td><td>" + show(at(o, "role")) +
           "</td><td>" + show(at(o, "lab")) + "</td><td>" + show(at(base, "sim")) + "</td><td>" +
           show(at(base, "residual"), "%+.4f") + "</td><td>" + show(at(o, "budget"), "%.4f") +
           "</td><td>" + show(at(o, "lab_uncertainty"), "%.4f") + "</td><td>" +
           show(at(at(o, "verdict"), "residual"), "%+.4f") + "</td></tr>\n";
  }
  return out + "</table>\n";
}

std::string residual_plot(const json& s) {
  BarChart chart;
  chart.y_label = "ln(sim / lab)";
  Series before{"base model", "#888", {}};
  const json& verdict = at(s, "verdict");
  std::string after_name =
      verdict["effect"].is_string() ? verdict["effect"].get<std::string>() : "";
  Series after{"with " + after_name, "#1f77b4", {}};
  for (const json& o : at(s, "observations")) {
    chart.categories.push_back(o["id"].get<std::string>() + " (" +
                               (o["role"] == "held_out" ? "held out" : "cal.") + ")");
    before.values.push_back(number(at(at(o, "base"), "residual")));
    after.values.push_back(number(at(at(o, "verdict"), "residual")));
    chart.band.push_back(number(at(o, "budget")) + number(at(o, "lab_uncertainty")));
  }
  chart.series.push_back(before);
  if (!after_name.empty()) chart.series.push_back(after);
  return "<h2>Residuals by observation, before and after</h2>\n" + legend_html(chart.series) +
         svg_bars(chart) +
         "<p class=\"note\">Grey band: budget + lab uncertainty of each observation.</p>\n";
}

std::string closure_plot(const json& s) {
  // Nothing to draw: the report's own reason, never an empty chart.
  const json& missing = at(at(s, "gap"), "closure_missing");
  if (missing.is_string()) {
    return "<h2>Gap closure per effect</h2>\n<p class=\"note\">No gap closure to show: " +
           show(missing) + ".</p>\n";
  }
  BarChart chart;
  chart.y_label = "gap closure G (held out)";
  Series confirmed{"confirmed by real runs", "#1f77b4", {}};
  Series surface{"on the surfaces", "#9ecae1", {}};
  Series hidden{"not identifiable", "#ccc", {}};
  for (const json& c : at(s, "candidates")) {
    if (!c["effect"].is_string()) continue;
    chart.categories.push_back(effect_name(c));
    const double g = number(at(at(c, "gap_closure"), "value"));
    const bool identifiable = at(c, "identifiable").is_boolean() && c["identifiable"].get<bool>();
    const bool real = at(at(c, "gap_closure"), "basis") == "confirmed";
    confirmed.values.push_back(identifiable && real ? g : NAN);
    surface.values.push_back(identifiable && !real ? g : NAN);
    hidden.values.push_back(identifiable ? NAN : g);
  }
  chart.series = {confirmed, surface, hidden};
  return "<h2>Gap closure per effect</h2>\n" + legend_html(chart.series) + svg_bars(chart);
}

// Each effect's evidence over the base model against the rule's threshold, then each model's
// held-out log predictive density term by term.
std::string evidence_section(const json& s) {
  BarChart chart;
  chart.y_label = "evidence over the base (nats, held out)";
  Series confirmed{"confirmed by real runs", "#1f77b4", {}};
  Series surface{"on the surfaces (+ their error)", "#9ecae1", {}};
  Series hidden{"not identifiable", "#ccc", {}};
  std::vector<std::string> held_out;
  for (const json& o : at(s, "observations")) {
    if (at(o, "role") == "held_out") held_out.push_back(o["id"].get<std::string>());
  }
  std::string rows;
  for (const json& c : at(s, "candidates")) {
    const json& e = at(c, "evidence");
    if (!e.is_object()) continue;
    rows += "<tr><td>" + escape_html(effect_name(c)) + "</td><td>" + show(at(e, "lpd"), "%.2f") +
            "</td><td>" + show(at(e, "value"), "%.2f") + "</td>";
    for (const std::string& id : held_out) {
      const json* term = nullptr;
      for (const json& t : at(e, "terms")) {
        if (t["id"] == id) term = &t;
      }
      rows += "<td>" + (term ? show(at(*term, "lpd"), "%.2f") : show(json(nullptr))) + "</td>";
    }
    rows += "<td>" + show(at(e, "basis")) + "</td></tr>\n";
    if (!c["effect"].is_string()) continue;
    chart.categories.push_back(effect_name(c));
    const double x = number(at(e, "value"));
    const bool identifiable = at(c, "identifiable") == true;
    const bool real = at(e, "basis") == "confirmed";
    confirmed.values.push_back(identifiable && real ? x : NAN);
    surface.values.push_back(identifiable && !real ? x : NAN);
    hidden.values.push_back(identifiable ? NAN : x);
  }
  if (rows.empty()) return "";
  std::string out = "<h2>Evidence per effect</h2>\n";
  const json& threshold = at(at(s, "decision"), "min_evidence");
  if (!chart.categories.empty()) {
    chart.series = {confirmed, surface, hidden};
    if (threshold.is_number()) {
      chart.lines = {{threshold.get<double>(), "threshold " + show(threshold, "%.2f")}};
    }
    out += legend_html(chart.series) + svg_bars(chart);
  }
  std::string head;
  for (const std::string& id : held_out) head += "<th>" + escape_html(id) + "</th>";
  return out +
         "<p>Held-out log predictive density (nats): each held-out charged residual r as a draw "
         "from N(0, v), v = budget&sup2; + lab uncertainty&sup2; (+ the surface's leave-one-out "
         "rms&sup2; where the prediction is from surfaces), term -&frac12;(r&sup2;/v + ln 2&pi;v). "
         "An effect's evidence is its density minus the base model's; it is named above " +
         show(threshold, "%.2f") +
         " nats.</p>\n<table><tr><th>model</th><th>lpd</th>"
         "<th>evidence</th>" +
         head + "<th>basis</th></tr>\n" + rows + "</table>\n";
}

std::string history_plot(const json& s) {
  LineChart chart;
  chart.x_label = "evaluation on the response surfaces";
  chart.y_label = "weighted misfit (best so far)";
  chart.log_y = true;
  int k = 0;
  for (const json& c : at(s, "candidates")) {
    Series series{effect_name(c), kPalette[k++ % 10], {}};
    for (const json& v : at(c, "history")) series.values.push_back(number(v));
    if (!series.values.empty()) chart.series.push_back(series);
  }
  return "<h2>Calibration history</h2>\n" + legend_html(chart.series) + svg_lines(chart);
}

// The next test's sentence, and per menu test its noise and how far apart it would put
// the leading pair and each effect the calibration cannot identify (noise units).
std::string next_test_section(const json& s) {
  const json& n = at(s, "next_test");
  if (!n.is_object()) return "";
  std::string out = "<h2>Next test</h2>\n<p>" + show(at(n, "reason")) + "</p>\n";
  if (n["enabled"] != true || !at(n, "menu").is_array() || at(n, "menu").empty()) return out;
  std::vector<const json*> columns;
  if (at(n, "leading").is_object()) columns.push_back(&n["leading"]);
  for (const json& row : at(n, "invisible")) columns.push_back(&row);
  out += "<table><tr><th>test</th><th>noise (budget, lab)</th>";
  for (const json* c : columns) {
    out += "<th>" + show(at(*c, "separates")[0]) + " vs " + show(at(*c, "separates")[1]) + "</th>";
  }
  out += "</tr>\n";
  for (const json& m : at(n, "menu")) {
    const json& noise = at(m, "noise");
    out += "<tr><td>" + show(at(m, "description")) + "</td><td>" +
           show(at(noise, "noise"), "%.3f") + " (" +
           (at(noise, "measured") == true ? std::string("measured")
                                          : "from " + show(at(noise, "budget_from"))) +
           ", from " + show(at(noise, "lab_uncertainty_from")) + ")</td>";
    const std::string id = at(m, "id").is_string() ? m["id"].get<std::string>() : "";
    for (const json* c : columns) {
      out += "<td>" + show(at(at(*c, "by_test"), id.c_str()), "%.2f") + "</td>";
    }
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

std::string candidates_table(const json& s) {
  const json& screen = at(at(s, "screen"), "reason");
  std::string out =
      "<h2>Candidates</h2>\n" +
      (screen.is_string() ? "<p>Screen: " + show(screen) + "</p>\n" : std::string()) +
      "<table><tr><th>rank</th><th>model</th><th>identifiable</th>"
      "<th>fits calibration</th>"
      "<th>moves</th><th>fitted parameter</th><th>F_r0</th><th>F_s0</th><th>evidence (nats)</th>"
      "<th>G</th><th>basis</th>"
      "<th>rms cal.</th><th>rms held out</th><th>surface leave-one-out rms (max)</th></tr>\n";
  // Base first (rank 0), then the effects in rank order.
  std::vector<json> ranked(at(s, "candidates").begin(), at(s, "candidates").end());
  std::stable_sort(ranked.begin(), ranked.end(), [](const json& a, const json& b) {
    return number(at(a, "rank")) < number(at(b, "rank"));
  });
  for (const json& c : ranked) {
    const json& p = at(c, "parameter");
    const json& rms = at(c, "rms");
    const json& which =
        at(rms, "confirmed").is_object() ? at(rms, "confirmed") : at(rms, "surface");
    double fit = 0;
    for (const json& v : at(c, "surface_loo_rms")) fit = std::max(fit, number(v));
    std::string moves;
    for (const json& m : at(c, "moves")) moves += (moves.empty() ? "" : ", ") + show(m);
    out += "<tr><td>" + (c["effect"].is_string() ? show(at(c, "rank")) : "") + "</td><td>" +
           escape_html(effect_name(c)) + "</td><td>" + show(at(c, "identifiable")) +
           (at(c, "identifiable_reason").is_string()
                ? "<br><small>" + show(at(c, "identifiable_reason")) + "</small>"
                : "") +
           "</td><td>" + show(at(c, "fits_calibration")) + "</td><td>" + moves + "</td><td>" +
           (p.is_object() ? show(at(p, "name")) + " = " + show(at(p, "value")) : "") + "</td><td>" +
           show(at(at(c, "fit"), "fr0")) + "</td><td>" + show(at(at(c, "fit"), "fs0")) +
           "</td><td>" + show(at(at(c, "evidence"), "value"), "%.2f") + "</td><td>" +
           show(at(at(c, "gap_closure"), "value"), "%.2f") + "</td><td>" +
           show(at(at(c, "gap_closure"), "basis")) + "</td><td>" +
           show(at(which, "calibration"), "%.4f") + "</td><td>" +
           show(at(which, "held_out"), "%.4f") + "</td><td>" + show(json(fit), "%.4f") +
           (c.contains("error") ? " " + show(c["error"]) : "") + "</td></tr>\n";
  }
  return out + "</table>\n";
}

// The real runs of each confirmed candidate: where the surfaces put it, where the run-corrected
// re-fits moved it, and the real calibration misfit at each (the smallest is the confirmed point).
std::string refinement_table(const json& s) {
  std::string rows;
  for (const json& c : at(s, "candidates")) {
    if (!at(c, "refinement").is_array()) continue;
    rows += "<tr><td>" + escape_html(effect_name(c)) + "</td>";
    for (const json& step : at(c, "refinement")) {
      rows += "<td>" + show(at(step, "fr0"), "%.1f") + ", " + show(at(step, "fs0"), "%.1f") +
              (step.contains("value") ? ", " + show(at(step, "value"), "%.3g") : "") + ": " +
              show(at(step, "misfit"), "%.3g") + "</td>";
    }
    rows += "</tr>\n";
  }
  if (rows.empty()) return "";
  return "<h2>Real runs of the confirmed candidates</h2>\n<p>Each run: F_r0, F_s0[, parameter]: "
         "real calibration misfit. The first is the fit on the surfaces; each next one the fit on "
         "the surfaces shifted through the previous run. The smallest misfit is confirmed.</p>\n"
         "<table>" +
         rows + "</table>\n";
}

std::string budget_table(const json& s) {
  const json& b = at(s, "budget");
  std::string out =
      "<h2>Numerical budget</h2>\n<p>Base model at its confirmed fit, F_r0 = " +
      show(at(at(b, "point"), "fr0")) + ", F_s0 = " + show(at(at(b, "point"), "fs0")) +
      ", and its neighbours (" + show(at(b, "points")) +
      " points in all) re-run with nothing physical changed; per observation the rms over the "
      "points of the |ln| change. The calibrations are weighted by the budget at the first fit, "
      "F_r0 = " +
      show(at(at(at(b, "weights"), "point"), "fr0")) +
      ", F_s0 = " + show(at(at(at(b, "weights"), "point"), "fs0")) + ".</p>\n" +
      "<table><tr><th>variant</th>";
  for (const json& o : at(s, "observations")) out += "<th>" + show(at(o, "id")) + "</th>";
  out += "</tr>\n";
  for (const json& v : at(b, "variants")) {
    out += "<tr><td>" + show(at(v, "name")) + "</td>";
    for (const json& o : at(s, "observations")) {
      out +=
          "<td>" + show(at(at(v, "change"), o["id"].get<std::string>().c_str()), "%.4f") + "</td>";
    }
    out += "</tr>\n";
  }
  out += "<tr><th>budget</th>";
  for (const json& o : at(s, "observations"))
    out += "<th>" + show(at(o, "budget"), "%.4f") + "</th>";
  out += "</tr>\n<tr><td>at the first fit (weights)</td>";
  for (const json& o : at(s, "observations")) {
    out += "<td>" +
           show(at(at(at(b, "weights"), "per_observation"), o["id"].get<std::string>().c_str()),
                "%.4f") +
           "</td>";
  }
  return out + "</tr></table>\n";
}

std::string ratio_section(const json& s) {
  const json& r = at(s, "ratio");
  if (!r.is_object()) return "";
  return "<h2>UCT/BTT ratio</h2>\n<p>Lab " + show(at(r, "lab"), "%.3g") + " (" +
         show(at(r, "uct")) + " / " + show(at(r, "btt")) + "); the base model reaches " +
         show(at(r, "min"), "%.3g") + " to " + show(at(r, "max"), "%.3g") + " over the bounds (" +
         show(at(r, "runs")) + " grid runs): the lab ratio is " +
         (at(r, "inside") == true ? "inside" : "outside") + " the attainable range.</p>\n";
}

// " Jobs: 120 of 134 planned (grid 54, budget 40, confirm 40)." from the progress model
// (orchestrator/progress_model.hpp): the count the CLI and the dashboard show.
std::string jobs_text(const json& model) {
  if (!at(model, "budget").is_number()) return "";
  return " Jobs: " + escape_html(summary::budget_count(model, " planned")) + ".";
}

// Where the figures of the verdict's runs go: the dashboard's own code (its report.js, with the
// job page's drawing) fills the element when the server serves this page; a copy opened without
// the server keeps the note.
std::string figures_section(const json& s) {
  const json& v = at(s, "verdict");
  if (!at(v, "fr0").is_number() || !at(v, "fs0").is_number()) return "";
  return "<h2>Fracture and stress-strain at the verdict's fit</h2>\n<p>The runs of the verdict's "
         "model (its effect, when it names one) at F_r0 = " +
         show(at(v, "fr0")) + ", F_s0 = " + show(at(v, "fs0")) +
         " N, drawn as the dashboard's job page draws a run: every broken bond of breaks.csv "
         "projected on the x-z plane by mode at the peak and at the end, and stress against strain "
         "from curve.csv.</p>\n<div class=\"figures\" data-figures-fr0=\"" +
         show(at(v, "fr0"), "%.17g") + "\" data-figures-fs0=\"" + show(at(v, "fs0"), "%.17g") +
         "\"><p class=\"note\">The server draws these when it serves this report "
         "(/api/v1/campaigns/ID/report.html); this copy was opened without it.</p></div>\n";
}

}  // namespace

std::string report_html(const json& s) {
  const std::string title = "Diagnosis: " + show(at(s, "name"));
  std::string out =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + title +
      "</title>\n<link rel=\"icon\" href=\"data:,\">\n<link rel=\"stylesheet\" "
      "href=\"/ui/style.css\">\n<script type=\"module\" "
      "src=\"/ui/report.js\"></"
      "script>\n<style>body{font-family:sans-serif;max-width:1000px;margin:2em auto;color:#222}"
      "table{border-collapse:collapse;margin:.5em 0;font-size:13px}td,th{border:1px solid #ccc;"
      "padding:3px 6px;text-align:left}tr.gap td{background:#fde0dc}.verdict{border:2px solid "
      "#1f77b4;padding:0 1em;margin:1em 0}.note{color:#666;font-size:12px}.legend "
      "span{margin-right:"
      "1.2em;font-size:12px}.legend i{display:inline-block;width:10px;height:10px;margin-right:4px}"
      "</style></head><body>\n<h1>" +
      title + "</h1>\n<p>Dataset " + show(at(s, "dataset")) +
      "; model units; every residual is ln(sim/lab). Engine runs: " +
      show(at(at(s, "runs"), "model_points")) + " model points, " +
      show(at(at(s, "runs"), "failed_values")) + " values missing" +
      (at(at(s, "runs"), "first_error").is_string()
           ? " (first: " + show(at(at(s, "runs"), "first_error")) + ")"
           : std::string()) +
      "; a run that ended without a peak is a failed run." + jobs_text(at(s, "progress")) +
      "</p>\n";
  out += verdict_section(s);
  out += gap_section(s);
  out += residual_plot(s);
  out += evidence_section(s);
  out += closure_plot(s);
  out += candidates_table(s);
  out += next_test_section(s);
  out += refinement_table(s);
  out += figures_section(s);
  out += history_plot(s);
  out += budget_table(s);
  out += ratio_section(s);
  out +=
      "<p class=\"note\">Method: docs/diagnosis.md. Response surfaces in (ln F_r0, ln F_s0[, s]) "
      "(a cubic radial-basis interpolant on a quadratic, smoothed by cross-validation) fitted to "
      "engine runs on a grid; every candidate calibrated on them; the "
      "base and the best candidates confirmed by real runs; effects ranked by their evidence "
      "on held-out observations only (log predictive density over the base model's); G, the "
      "held-out gap closure, shown beside it.</p>\n</body></html>\n";
  return out;
}

}  // namespace rockcal::diagnosis
