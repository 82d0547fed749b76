#include "orchestrator/diagnosis/analysis/test_menu.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

namespace rockcal::diagnosis {
namespace {

const Target* first_of(const std::vector<Target>& targets, auto&& wanted) {
  const auto it = std::find_if(targets.begin(), targets.end(), wanted);
  return it == targets.end() ? nullptr : &*it;
}

// The cylinder the menu varies: the first calibration UCT's, else any UCT's or triaxial's.
RunConditions specimen_of(const std::vector<Target>& targets) {
  auto uct = [](const Target& t) { return t.conditions.test == TestKind::uct; };
  const Target* t =
      first_of(targets, [&](const Target& x) { return uct(x) && x.role == Role::calibration; });
  if (!t) t = first_of(targets, uct);
  if (!t) t = first_of(targets, [](const Target& x) { return is_triaxial(x.conditions.test); });
  RunConditions c = t ? t->conditions : targets.front().conditions;
  c.test = TestKind::uct;
  c.confining_pressure_pa = 0;
  if (!t) c.height_m = 2 * c.diameter_m;
  return c;
}

// The dataset's UCS (Pa, model units) from its first UCT peak load or strength, if it has one.
std::optional<double> ucs_of(const std::vector<Target>& targets) {
  const Target* t = first_of(targets, [](const Target& x) {
    return x.conditions.test == TestKind::uct &&
           (x.observable == Observable::peak_load || x.observable == Observable::strength);
  });
  if (!t) return std::nullopt;
  if (t->observable == Observable::strength) return t->value;
  const double d = t->conditions.diameter_m;
  return t->value / (M_PI * d * d / 4);
}

bool already_has(const std::vector<Target>& targets, const Target& m) {
  return std::any_of(targets.begin(), targets.end(), [&](const Target& t) {
    if (t.observable != m.observable || t.conditions.test != m.conditions.test) return false;
    if (!is_triaxial(m.conditions.test)) return t.conditions == m.conditions;
    const double p = t.conditions.confining_pressure_pa, q = m.conditions.confining_pressure_pa;
    return std::abs(p - q) <= 0.1 * std::max(p, q);
  });
}

std::string text(const char* format, double x) {
  char line[128];
  std::snprintf(line, sizeof line, format, x);
  return line;
}

}  // namespace

std::vector<MenuTest> test_menu(const std::vector<Target>& targets) {
  if (targets.empty()) return {};
  const RunConditions cylinder = specimen_of(targets);
  RunConditions disc = cylinder;
  disc.test = TestKind::btt;
  disc.thickness_m = 0.5 * cylinder.diameter_m;
  if (const Target* b =
          first_of(targets, [](const Target& x) { return x.conditions.test == TestKind::btt; })) {
    disc = b->conditions;
  }
  std::vector<MenuTest> menu;
  auto add = [&](std::string id, Observable o, const RunConditions& c, std::string description) {
    MenuTest m;
    m.target.id = "menu-" + std::move(id);
    m.target.observable = o;
    m.target.role = Role::held_out;
    m.target.conditions = c;
    m.description = std::move(description);
    if (!already_has(targets, m.target)) menu.push_back(std::move(m));
  };
  for (double hd : {1.0, 3.0}) {
    RunConditions c = cylinder;
    c.height_m = hd * c.diameter_m;
    add(text("uct-hd%g", hd), Observable::peak_load, c,
        text(hd < 2 ? "the peak load of a squat UCT (H/D = %g)"
                    : "the peak load of a slender UCT (H/D = %g)",
             hd));
  }
  add("uct-modulus", Observable::youngs_modulus, cylinder, "the UCT's Young's modulus");
  add("uct-peak-strain", Observable::peak_strain, cylinder, "the UCT's axial strain at the peak");
  for (double f : {0.5, 2.0}) {
    RunConditions c = disc;
    c.thickness_m = f * disc.thickness_m;
    add(text("btt-t%g", f), Observable::peak_load, c,
        text("the peak load of a disc of %g x the thickness", f));
  }
  // At 4x the platen speed: a model loaded too fast gains strength with speed that the lab's rock
  // (nearly rate-independent at these speeds) does not, and the disc shows it most.
  for (RunConditions c : {cylinder, disc}) {
    c.platen_velocity_m_s *= kMenuSpeedFactor;
    const bool uct = c.test == TestKind::uct;
    add(uct ? "uct-fast" : "btt-fast", Observable::peak_load, c,
        text(uct ? "the peak load of a UCT at %g x the platen speed"
                 : "the peak load of a disc at %g x the platen speed",
             kMenuSpeedFactor));
  }
  const std::optional<double> ucs = ucs_of(targets);
  if (!ucs) return menu;
  const Target* triaxial =
      first_of(targets, [](const Target& x) { return is_triaxial(x.conditions.test); });
  const Observable tri_observable = triaxial && triaxial->observable == Observable::strength
                                        ? Observable::strength
                                        : Observable::peak_load;
  for (double f : kMenuConfinements) {
    RunConditions c = cylinder;
    c.test = TestKind::triaxial;
    c.confining_pressure_pa = f * *ucs;
    add(text("tri-%gucs", f), tri_observable, c,
        text(tri_observable == Observable::strength
                 ? "the strength (sigma_1 at the peak) of a triaxial test at %g x the UCS"
                 : "the peak load of a triaxial test at %g x the UCS",
             f));
  }
  return menu;
}

std::vector<Target> with_menu(std::vector<Target> targets, const std::vector<MenuTest>& menu) {
  for (const MenuTest& m : menu) targets.push_back(m.target);
  return targets;
}

}  // namespace rockcal::diagnosis
