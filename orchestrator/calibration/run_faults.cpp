#include "orchestrator/calibration/run_faults.hpp"

#include "orchestrator/calibration/sentence.hpp"

namespace rockcal::calibration {
namespace {

// Every realisation of both tests of every evaluation, or the evaluation's own error when its
// evaluator reports no realisations.
template <typename Visit>
void each_run(const std::vector<EvaluationRecord>& history, Visit visit) {
  for (const EvaluationRecord& e : history) {
    if (!e.uct || !e.btt) {
      visit(e.error, std::optional<bool>());
      continue;
    }
    for (const orch::Ensemble* test : {&*e.uct, &*e.btt})
      for (const orch::Realisation& x : test->realisations) visit(x.error, x.quasi_static);
  }
}

}  // namespace

bool is_no_peak(const std::string& error) {
  return error.rfind("no peak", 0) == 0 || error.find(": no peak") != std::string::npos;
}

// The search's runs that ended without a peak (failed jobs "no peak: ..."; their largest load is
// no result), by the limit that ended them, with the fix. Empty when every run reached one.
std::string no_peak_text(const std::vector<EvaluationRecord>& history) {
  int runs = 0, no_peak = 0, at_strain = 0, at_steps = 0, past_window = 0;
  auto count = [&](const std::string& error) {
    ++runs;
    if (!is_no_peak(error)) return;
    ++no_peak;
    at_strain += error.find("loading.max_strain") != std::string::npos ? 1 : 0;
    at_steps += error.find("loading.max_steps") != std::string::npos ? 1 : 0;
    past_window += error.find("loading.past_window") != std::string::npos ? 1 : 0;
  };
  each_run(history, [&](const std::string& error, std::optional<bool>) { count(error); });
  if (no_peak == 0) return "";
  std::string out =
      sentence("%.0f of %.0f runs ended without a peak and count as failed", no_peak, runs);
  if (at_strain > 0)
    out += sentence(
        " (%.0f at loading.max_strain: raise it in the job template so that they "
        "reach one",
        at_strain);
  if (at_steps > 0)
    out +=
        (at_strain > 0 ? "; " : " (") + sentence("%.0f at loading.max_steps: raise it", at_steps);
  if (past_window > 0)
    out += (at_strain + at_steps > 0 ? "; " : " (") +
           sentence(
               "%.0f still loading up past the bond-controlled window: no peak set by the bond "
               "strengths there",
               past_window);
  if (at_strain + at_steps + past_window > 0) out += ")";
  return out;
}

nlohmann::json platen_velocity_of(const CalibrationCampaign& c) {
  const nlohmann::json& loading = c.job_template.value("loading", nlohmann::json::object());
  return loading.is_object() ? loading.value("platen_velocity", nlohmann::json())
                             : nlohmann::json();
}

std::string not_quasi_static_text(const std::vector<EvaluationRecord>& history,
                                  const nlohmann::json& platen_velocity) {
  int measured = 0, slow_enough = 0;
  each_run(history, [&](const std::string&, std::optional<bool> quasi_static) {
    if (!quasi_static) return;
    ++measured;
    slow_enough += *quasi_static ? 1 : 0;
  });
  const int fast = measured - slow_enough;
  if (fast == 0) return "";
  std::string out = sentence(
      "%.0f of %.0f runs that reported it were not quasi-static (their platen closed the bonds' "
      "failure strain in fewer wave transits than the engine's threshold), so their peaks are "
      "raised by the loading rate",
      fast, measured);
  out += platen_velocity.is_string()
             ? ": raise loading.auto_transits"
             : ": set loading.platen_velocity to \"auto\" (or lower it) in the job template";
  return out;
}

}  // namespace rockcal::calibration
