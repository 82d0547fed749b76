#include "orchestrator/diagnosis/report/next_test_json.hpp"

#include <cmath>
#include <cstdio>

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

json num(double x) {
  return std::isfinite(x) ? json(x) : json(nullptr);
}

std::string hypothesis(const std::string& effect) {
  return effect.empty() ? "the base model" : effect;
}

// A menu test's conditions in the dataset's units (lab units: m and Pa by eq. 4; the platen speed
// is the model's and is left out there, since a lab loads quasi-statically).
json conditions_json(const RunConditions& c, const Dataset& d) {
  const bool lab = d.scaling.has_value();
  auto length = [&](double x) { return lab ? d.scaling->length_to_lab(x) : x; };
  json j = {{"units", lab ? "lab" : "model"}, {"diameter", length(c.diameter_m)}};
  if (c.test == TestKind::btt) {
    j["thickness"] = length(c.thickness_m);
  } else {
    j["height"] = length(c.height_m);
  }
  if (is_triaxial(c.test)) {
    j["confining_pressure"] =
        lab ? d.scaling->stress_to_lab(c.confining_pressure_pa) : c.confining_pressure_pa;
  }
  if (!lab) j["platen_velocity"] = c.platen_velocity_m_s;
  return j;
}

std::string conditions_text(const json& c) {
  char line[256];
  const bool disc = c.contains("thickness");
  std::snprintf(line, sizeof line, "diameter %.4g m, %s %.4g m", c["diameter"].get<double>(),
                disc ? "thickness" : "height", c[disc ? "thickness" : "height"].get<double>());
  std::string out = line;
  if (c.contains("confining_pressure")) {
    std::snprintf(line, sizeof line, ", confinement %.4g Pa",
                  c["confining_pressure"].get<double>());
    out += line;
  }
  return out + (c["units"] == "lab" ? " (lab units)" : " (model units)");
}

json noise_json(const TestNoise& n) {
  return {{"budget", n.budget},
          {"budget_from", n.measured_by.empty() ? json(n.budget_from) : json(nullptr)},
          {"measured", !n.measured_by.empty()},
          {"measured_by", n.measured_by},
          {"lab_uncertainty", n.sigma},
          {"lab_uncertainty_from", n.sigma_from},
          {"noise", n.total()}};
}

// Where a test's budget comes from: "measured at the fit (N variants)" or "borrowed from ID".
std::string budget_source(const json& noise) {
  if (noise["measured"].get<bool>()) {
    const std::size_t k = noise["measured_by"].size();
    return "measured at the fit over " + std::to_string(k) +
           (k == 1 ? " budget variant" : " budget variants");
  }
  return "borrowed from " + noise["budget_from"].get<std::string>();
}

// The run of one hypothesis behind a test: its model point and its value there.
json run_json(const NextTest& next, const DiagnosisCampaign& c, const std::string& effect,
              std::size_t test) {
  const std::size_t run = run_of(next, effect);
  const ModelPoint& p = next.runs[run].point;
  json j = {{"hypothesis", hypothesis(effect)},
            {"fr0", p.fr0_n},
            {"fs0", p.fs0_n},
            {"effect", effect.empty() ? json(nullptr) : json(effect)},
            {"s", p.s},
            {"sim", num(std::exp(next.ln[run][test]))}};
  for (const Candidate& k : c.candidates) {
    if (k.effect == effect && k.value_at) {
      j["parameter"] = {{"name", k.param}, {"unit", k.unit}, {"value", k.value_at(p.s)}};
    }
  }
  const std::vector<double> mark = mark_of(next, effect);
  j["mark"] = mark.empty() ? json(nullptr) : num(mark[test]);
  return j;
}

// One separation: the best test, its discrimination, the runs, every test's discrimination.
json separation_json(const Separation& s, const NextTest& next, const DiagnosisCampaign& c) {
  json by_test = json::object();
  for (std::size_t m = 0; m < next.menu.size(); ++m) {
    by_test[next.menu[m].target.id] = num(s.discrimination[m]);
  }
  json j = {{"separates", {hypothesis(s.a), hypothesis(s.b)}}, {"by_test", by_test}};
  if (!s.best) {
    j["test"] = nullptr;
    return j;
  }
  const std::size_t m = *s.best;
  const MenuTest& t = next.menu[m];
  j["test"] = {{"id", t.target.id},
               {"description", t.description},
               {"test", to_string(t.target.conditions.test)},
               {"observable", to_string(t.target.observable)},
               {"conditions", conditions_json(t.target.conditions, c.dataset)}};
  j["discrimination"] = s.discrimination[m];
  j["visible"] = s.visible;
  j["noise"] = noise_json(next.noise[m]);
  j["runs"] = {run_json(next, c, s.a, m), run_json(next, c, s.b, m)};
  return j;
}

std::string pair_sentence(const json& s) {
  if (s["test"].is_null()) {
    return "no test on the menu gave values for " + s["separates"][0].get<std::string>();
  }
  char line[512];
  const json& n = s["noise"];
  std::snprintf(line, sizeof line,
                "%s (%s) would separate %s from %s by %.2f noise units (their marks %+.3f and "
                "%+.3f in ln; noise %.3f: budget %.3f %s, lab uncertainty %.3f from "
                "%s)",
                s["test"]["description"].get<std::string>().c_str(),
                conditions_text(s["test"]["conditions"]).c_str(),
                s["separates"][0].get<std::string>().c_str(),
                s["separates"][1].get<std::string>().c_str(), s["discrimination"].get<double>(),
                s["runs"][0]["mark"].is_number() ? s["runs"][0]["mark"].get<double>() : NAN,
                s["runs"][1]["mark"].is_number() ? s["runs"][1]["mark"].get<double>() : NAN,
                n["noise"].get<double>(), n["budget"].get<double>(), budget_source(n).c_str(),
                n["lab_uncertainty"].get<double>(),
                n["lab_uncertainty_from"].get<std::string>().c_str());
  // The best test of all may still leave the two within one noise of each other.
  if (!s["visible"].get<bool>()) {
    return std::string(line) +
           "; their marks part by less than budget + lab uncertainty, so no test on the menu "
           "tells them apart";
  }
  return line;
}

}  // namespace

json next_test_json(const NextTest& next, const DiagnosisCampaign& c,
                    const std::vector<std::string>& fit_on_bounds) {
  if (!next.enabled) {
    return {{"enabled", false}, {"reason", "not asked for (\"next_test\": false)"}};
  }
  json menu = json::array();
  for (std::size_t m = 0; m < next.menu.size(); ++m) {
    const MenuTest& t = next.menu[m];
    json row = {{"id", t.target.id},
                {"description", t.description},
                {"test", to_string(t.target.conditions.test)},
                {"observable", to_string(t.target.observable)},
                {"conditions", conditions_json(t.target.conditions, c.dataset)}};
    if (m < next.noise.size()) row["noise"] = noise_json(next.noise[m]);
    menu.push_back(std::move(row));
  }
  // Every model point of the batch (each one job per distinct condition of dataset and menu).
  json runs = json::array();
  for (const RunRequest& r : next.runs) {
    runs.push_back({{"fr0", r.point.fr0_n},
                    {"fs0", r.point.fs0_n},
                    {"effect", effect_on(r.point) ? json(r.point.effect) : json(nullptr)},
                    {"s", r.point.s}});
  }
  json j = {{"enabled", true},
            {"menu", menu},
            {"model_points", next.model_points},
            {"runs", runs},
            {"point", {{"fr0", next.point.fr0_n}, {"fs0", next.point.fs0_n}}}};
  if (!next.reason.empty()) {
    j["leading"] = nullptr;
    j["invisible"] = json::array();
    j["reason"] = next.reason;
    return j;
  }
  // Appends `text` to `to`, after `separator` unless `to` is empty.
  auto append = [](std::string& to, const char* separator, const std::string& text) {
    if (!to.empty()) to += separator;
    to += text;
  };
  std::string reason;
  j["leading"] = next.leading ? separation_json(*next.leading, next, c) : json(nullptr);
  if (next.leading) reason = pair_sentence(j["leading"]) + ".";
  json invisible = json::array();
  std::string shown, unseen;
  char line[64];
  for (const Separation& s : next.invisible) {
    json row = separation_json(s, next, c);
    row["effect"] = s.a;
    row["why"] = s.why;
    // An effect the leading pair already sets against the base model on the same test is said once.
    const bool said = next.leading && next.leading->b.empty() && next.leading->a == s.a &&
                      next.leading->best == s.best;
    if (said) {
      // Already in the first sentence.
    } else if (row["test"].is_object() && row["visible"] == true) {
      std::snprintf(line, sizeof line, ", %.2f noise units", row["discrimination"].get<double>());
      append(shown, "; ",
             s.a + ": " + row["test"]["description"].get<std::string>() + " (" +
                 conditions_text(row["test"]["conditions"]) + line + ")");
    } else {
      append(unseen, ", ", s.a);
    }
    invisible.push_back(std::move(row));
  }
  if (!shown.empty()) {
    append(reason, " ",
           std::string(judges_effects(c) ? "For the effects the calibration observations cannot "
                                           "identify (next_test.invisible[].why)"
                                         : "With nothing held out no effect can be judged "
                                           "(next_test.invisible[].why); for each") +
               ", the test that would show it against the base model: " + shown + ".");
  }
  if (!unseen.empty()) {
    append(reason, " ",
           "No test on the menu shows " + unseen + " beyond budget + lab uncertainty.");
  }
  j["invisible"] = invisible;
  j["fit_on_bounds"] = fit_on_bounds;
  if (!fit_on_bounds.empty() && !reason.empty()) {
    std::string where;
    for (const std::string& b : fit_on_bounds) append(where, ", ", b);
    append(reason, " ",
           "The base model's fit lies on the search box (" + where +
               "): the marks are measured there and the strengths' re-fit extrapolates past the "
               "bound, so these figures rank the tests but may overstate how far apart they put "
               "the hypotheses; widen the bounds and diagnose again for their size.");
  }
  j["reason"] = reason;
  return j;
}

}  // namespace rockcal::diagnosis
