#include "orchestrator/calibration/fidelity.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "orchestrator/calibration/search_space.hpp"

namespace rockcal::calibration {
namespace {

// Coarse evaluations within this distance (in ln F_r0, ln F_s0) of the best point fit the Jacobian.
constexpr double kNeighbourhood = 0.7;

// d ln(load) / d (ln F_r0, ln F_s0) of the coarse model near `best`, by least squares on the
// evaluations around it; nullopt when they do not span two directions.
std::optional<Eigen::Matrix2d> coarse_jacobian(const std::vector<EvaluationRecord>& coarse,
                                               const EvaluationRecord& best, int& used) {
  // Normal equations of ln L = a + J (du, dv), fixed-size (3 unknowns per load).
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, 2> aty = Eigen::Matrix<double, 3, 2>::Zero();
  const double u0 = std::log(best.point.fr0_n), v0 = std::log(best.point.fs0_n);
  used = 0;
  for (const EvaluationRecord& r : coarse) {
    if (!r.loads) continue;
    const double du = std::log(r.point.fr0_n) - u0, dv = std::log(r.point.fs0_n) - v0;
    if (std::hypot(du, dv) > kNeighbourhood) continue;
    const Eigen::Vector3d row(1.0, du, dv);
    ata += row * row.transpose();
    aty += row * Eigen::RowVector2d(std::log(r.loads->uct_n), std::log(r.loads->btt_n));
    ++used;
  }
  if (used < 4) return std::nullopt;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(ata);
  const Eigen::Vector3d ev = eig.eigenvalues();      // ascending
  if (!(ev(0) > 1e-6 * ev(2))) return std::nullopt;  // the points lie on a line
  const Eigen::Matrix<double, 3, 2> coef = ata.ldlt().solve(aty);
  Eigen::Matrix2d j;
  j << coef(1, 0), coef(2, 0), coef(1, 1), coef(2, 1);  // rows: uct, btt; columns: u, v
  if (std::abs(j.determinant()) < 1e-6) return std::nullopt;
  return j;
}

// Broyden's update: the least change of J that reproduces the measured secant df = J dx. Kept
// only when the result can still be inverted (a step along which the loads did not move would
// make it singular).
void secant_update(Eigen::Matrix2d& j, const Eigen::Vector2d& dx, const Eigen::Vector2d& df,
                   int& updates) {
  const double dx2 = dx.squaredNorm();
  if (!(dx2 > 1e-12)) return;
  const Eigen::Matrix2d next = j + (df - j * dx) * dx.transpose() / dx2;
  if (!(std::abs(next.determinant()) >= 1e-6)) return;
  j = next;
  ++updates;
}

}  // namespace

std::optional<FidelityResult> correct_on_fine(const std::vector<EvaluationRecord>& coarse,
                                              const EvaluationRecord& best,
                                              const CalibrationCampaign& c, double degree,
                                              Evaluator& evaluator) {
  if (c.fine_patch.is_null() || !best.loads) return std::nullopt;
  FidelityResult out;
  int used = 0;
  std::optional<Eigen::Matrix2d> jac = coarse_jacobian(coarse, best, used);
  out.jacobian = jac ? "fitted to " + std::to_string(used) + " coarse evaluations"
                     : "scale only (the coarse evaluations near the best point span one direction)";
  const PeakLoads& t = c.targets.model_loads_n;
  BondPoint point = best.point;
  std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> last;  // (ln x, ln fine loads)
  for (int k = 0; k < c.fine_corrections; ++k) {
    // Newton works in the search's strengths; the fine specimen runs them scaled.
    const BondPoint fine_point{point.fr0_n * c.fine_strength_scale,
                               point.fs0_n * c.fine_strength_scale};
    const ProbeRequest probes[2] = {
        {fine_point, c.sample_seed, c.realisations, TestKind::uct, c.fine_patch},
        {fine_point, c.sample_seed, c.realisations, TestKind::btt, c.fine_patch}};
    const std::vector<orch::Ensemble> e = evaluator.probe_batch(probes);
    FidelityStep step{fine_point, std::nullopt, {0.0, 0.0}, "", false};
    if (e.size() < 2 || !e[0].peak_load.mean || !e[1].peak_load.mean) {
      step.error = e.size() < 2 ? "the evaluator runs no fine specimen"
                                : "a fine run ended without a peak load";
      out.steps.push_back(step);
      break;
    }
    step.fine = PeakLoads{*e[0].peak_load.mean, *e[1].peak_load.mean};
    step.rel_se = {orch::relative_se(e[0].peak_load), orch::relative_se(e[1].peak_load)};
    step.within_tolerance = within_tolerance(*step.fine, t, c.tolerance, step.rel_se);
    if (k == 0)
      out.factors =
          PeakLoads{step.fine->uct_n / best.loads->uct_n, step.fine->btt_n / best.loads->btt_n};
    out.steps.push_back(step);
    if (step.within_tolerance) {
      out.met = true;
      break;
    }
    const Eigen::Vector2d x(std::log(point.fr0_n), std::log(point.fs0_n));
    const Eigen::Vector2d f(std::log(step.fine->uct_n), std::log(step.fine->btt_n));
    if (jac && last) secant_update(*jac, x - last->first, f - last->second, out.secant_updates);
    last = {x, f};
    const LogErrors err = log_errors(*step.fine, t);
    Eigen::Vector2d dx;
    if (jac) {
      dx = jac->inverse() * Eigen::Vector2d(-err.uct, -err.btt);
    } else {
      const double shift = scale_shift(err, {c.weight_uct, c.weight_btt}, degree);
      dx = {shift, shift};
    }
    // A step of more than a factor e in either strength is not trusted from a local fit.
    const double longest = dx.cwiseAbs().maxCoeff();
    if (longest > 1.0) dx /= longest;
    point = clip_to_bounds({point.fr0_n * std::exp(dx(0)), point.fs0_n * std::exp(dx(1))}, c);
  }
  return out;
}

nlohmann::json to_json(const FidelityResult& r, const CalibrationCampaign& c) {
  nlohmann::json steps = nlohmann::json::array();
  for (const FidelityStep& s : r.steps) {
    nlohmann::json j = {{"fr0", s.point.fr0_n},
                        {"fs0", s.point.fs0_n},
                        {"resolution", "fine"},
                        {"within_tolerance", s.within_tolerance},
                        {"error", s.error}};
    if (s.fine) {
      j["uct"] = {{"peak_load", s.fine->uct_n},
                  {"relative_error", s.fine->uct_n / c.targets.model_loads_n.uct_n - 1},
                  {"relative_se", s.rel_se.uct_n}};
      j["btt"] = {{"peak_load", s.fine->btt_n},
                  {"relative_error", s.fine->btt_n / c.targets.model_loads_n.btt_n - 1},
                  {"relative_se", s.rel_se.btt_n}};
    }
    steps.push_back(j);
  }
  return {
      {"fine", c.fine_patch},
      {"strength_scale", c.fine_strength_scale},
      {"steps", steps},
      {"met", r.met},
      {"jacobian", r.jacobian},
      {"secant_updates", r.secant_updates},
      {"factors", r.factors ? nlohmann::json{{"uct", r.factors->uct_n}, {"btt", r.factors->btt_n}}
                            : nlohmann::json(nullptr)}};
}

}  // namespace rockcal::calibration
