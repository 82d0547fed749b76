// The next test: which lab test from the menu (test_menu.hpp) would best tell two hypotheses apart,
// and which one would make an effect visible that the calibration observations cannot identify.
//
// Each effect runs at its strong value (s = 1) at the base model's fit, as the screen does, on the
// dataset's and the menu's conditions. Its mark on a menu test is its ln change from the base
// model's run there left after the strengths' linear re-fit (change_after_refit) to the calibration
// observations and that test: what the test would still show once it joins the calibration. (A
// re-fit to the calibration alone overstates it for a test whose change the strengths can take up
// where the calibration pins them loosely: the engine's compression-coupling twin, whose slender
// UCT, named so, moved the fit and then showed nothing; docs/diagnosis-measurements.md.) The
// expected discrimination of a test between hypotheses A and B (an effect, or the base model with a
// mark of 0) is |mark_A - mark_B| / sqrt(budget^2 + sigma^2): how many noise units apart the two
// would put its lab value. A test the dataset does not have has no budget from the dataset's: its
// budget is measured at the base fit by the budget's variants (next_test_runs.hpp), and where they
// gave no value it borrows the largest budget of the dataset's observations of the same test and
// observable (else of the same test, else of any), and says which; its lab uncertainty, which no
// run can measure, is borrowed so always.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/budget.hpp"
#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/analysis/test_menu.hpp"

namespace rockcal::diagnosis {

struct TestNoise {
  double budget = 0.0;      // numerical, in ln
  std::string budget_from;  // the observation it is borrowed from ("" when measured)
  double sigma = 0.0;       // lab uncertainty, relative
  std::string sigma_from;
  std::vector<std::string> measured_by;  // the budget variants that measured it at the base fit
  double total() const;                  // sqrt(budget^2 + sigma^2)
};
TestNoise borrowed_noise(const Target& test, const std::vector<Target>& targets,
                         const std::vector<double>& budget);
// The budget measured at the base fit on the dataset's n targets and then the menu's: each menu
// test it measured takes that budget in place of the borrowed one, with the variants that gave it
// a value.
void use_measured_budgets(std::vector<TestNoise>& noise, const Budget& measured, std::size_t n);

// Two hypotheses on every menu test. `a` and `b` are effect names ("" = the base model).
struct Separation {
  std::string a, b;
  std::vector<double> discrimination;  // per menu test; NaN where a run gave no value
  // The menu test with the largest discrimination among those where the marks part beyond budget +
  // lab uncertainty (the bar identifiability sets), else the largest of all.
  std::optional<std::size_t> best;
  bool visible = false;  // `best` clears that bar, so that test would see an effect against base
  std::string why;       // for an effect the calibration cannot identify: why not
};
// mark_a, mark_b: per menu test, as above (empty = the base model's zeros).
Separation separate(std::string a, std::string b, const std::vector<double>& mark_a,
                    const std::vector<double>& mark_b, const std::vector<TestNoise>& noise);

// The base model's runs that start the batch: at the fit, and a step along each strength.
inline constexpr std::size_t kNextTestBaseRuns = 3;

struct NextTest {
  bool enabled = false;
  std::string reason;  // why there is no next test, when there is none
  ModelPoint point;    // the base model's fit, where every run is but those below
  std::vector<MenuTest> menu;
  std::vector<TestNoise> noise;  // per menu test
  // The runs behind it: the base model at the fit and at a step along each strength (the menu
  // tests' strength response), then each effect at s = 1 (at the screen's balanced point for one
  // seen only there, then the base's three runs there), then the base at the fit under each budget
  // variant (the menu's budgets); ln[run][menu test].
  std::vector<RunRequest> runs;
  std::vector<std::vector<double>> ln;
  std::vector<std::string> effects;       // the effects with a mark
  std::vector<std::vector<double>> mark;  // [effect][menu test]
  std::optional<Separation> leading;      // the two leading hypotheses
  std::vector<Separation> invisible;      // effects the calibration cannot identify, vs base
  int model_points = 0;
};

// An effect's marks on the menu tests (joined_marks[m]: as above, with menu test m, targets[n + m],
// weighted as a calibration observation, refit_weight). change, jacobian, weight and targets span
// the dataset's n targets (weight 0 but for calibration) and then the menu's.
std::vector<double> joined_marks(const std::vector<double>& change,
                                 const std::vector<std::array<double, 2>>& jacobian,
                                 const std::vector<double>& weight,
                                 const std::vector<Target>& targets, std::size_t n);

// The run of a hypothesis in NextTest::runs: the base model's at the fit for "", else the effect's.
std::size_t run_of(const NextTest& next, const std::string& effect);
// Its mark per menu test: zeros for the base model; empty for an effect without runs.
std::vector<double> mark_of(const NextTest& next, const std::string& effect);

}  // namespace rockcal::diagnosis
