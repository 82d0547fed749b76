#include "orchestrator/calibration/consistent_set.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "orchestrator/calibration/search_space.hpp"
#include "orchestrator/calibration/sentence.hpp"

namespace rockcal::calibration {
namespace {

// The scale on ratio `s` that best fits both loads, predicted from an evaluated point.
double fitted_m(const EvaluationRecord& r, const Ledger& ledger, double degree) {
  return ratio_coords(r.point).m +
         scale_shift(log_errors(*r.loads, ledger.targets()), ledger.weights(), degree);
}

enum class Try { member, missed, budget, failed };

// One ratio of the walk. The first guess of the scale continues the valley through the members
// nearest in ratio (the last member's scale when there is one only); when that misses, the scale
// that fits both loads there.
class Walk {
 public:
  Walk(Ledger& ledger, const CalibrationCampaign& c, const EvaluationRecord& from, double degree,
       int budget)
      : ledger_(ledger), box_(log_box(c)), degree_(degree), budget_(budget) {
    members_.push_back(ratio_coords(from.point));
  }

  Try at(double s) {
    const Range mr = m_range(box_, s);
    double m = guess_m(s);
    for (bool refitted = false;; refitted = true) {
      if (budget_ <= 0 || ledger_.remaining() <= 0) return Try::budget;
      --budget_;
      const EvaluationRecord r = ledger_.evaluate_one(point_from_ratio_coords({s, m}), "valley");
      if (!r.loads) return Try::failed;
      if (r.within_tolerance) {
        members_.push_back(ratio_coords(r.point));
        return Try::member;
      }
      const double refit = clamp_to(fitted_m(r, ledger_, degree_), mr);
      if (refitted || std::abs(refit - m) < 1e-9) return Try::missed;
      m = refit;
    }
  }

 private:
  double guess_m(double s) const {
    std::vector<RatioCoords> near = members_;
    std::sort(near.begin(), near.end(), [s](const RatioCoords& a, const RatioCoords& b) {
      return std::abs(a.s - s) < std::abs(b.s - s);
    });
    double m = near[0].m;
    if (near.size() >= 2 && std::abs(near[1].s - near[0].s) > 1e-9)
      m += (near[1].m - near[0].m) / (near[1].s - near[0].s) * (s - near[0].s);
    return clamp_to(m, m_range(box_, s));
  }

  Ledger& ledger_;
  LogBox box_;
  double degree_;
  int budget_;
  std::vector<RatioCoords> members_;
};

TraceEnd end_of(Try t) {
  return t == Try::budget ? TraceEnd::budget : TraceEnd::failed;
}

// One direction: ratio offsets growing as ln(kRatioStep) x 1, 3, 6, 10, ... (the first step decides
// uniqueness, the growth reaches a long valley's end in few evaluations), the last at the bound;
// then the end between the last member and the first miss bisected kEndBisections times.
constexpr int kEndBisections = 2;

TraceEnd walk(Ledger& ledger, const CalibrationCampaign& c, const EvaluationRecord& from,
              double direction, double degree, int budget) {
  const Range sr = s_range(log_box(c));
  const double s0 = ratio_coords(from.point).s;
  const double limit = direction > 0 ? sr.hi - s0 : s0 - sr.lo;  // offset to the bound
  const double step = std::log(kRatioStep);
  Walk w(ledger, c, from, degree, budget);
  double inside = 0.0, outside = 0.0;
  for (int k = 1;; ++k) {
    const double offset = std::min(step * k * (k + 1) / 2, limit);
    if (offset <= inside + 1e-12) return TraceEnd::bounds;
    const Try t = w.at(s0 + direction * offset);
    if (t == Try::member) {
      inside = offset;
      if (offset >= limit) return TraceEnd::bounds;
      continue;
    }
    if (t != Try::missed) return end_of(t);
    outside = offset;
    break;
  }
  for (int i = 0; i < kEndBisections && outside - inside > step; ++i) {
    const double mid = 0.5 * (inside + outside);
    const Try t = w.at(s0 + direction * mid);
    if (t == Try::member)
      inside = mid;
    else if (t == Try::missed)
      outside = mid;
    else
      break;
  }
  return TraceEnd::missed;
}

// ln of the point's UCT/BTT load ratio over the targets': zero on the valley, at any scale of a
// homogeneous model.
double ratio_gap(const EvaluationRecord& r, const PeakLoads& t) {
  return std::log((r.loads->uct_n / r.loads->btt_n) / (t.uct_n / t.btt_n));
}

// The valley can have several branches (a tensile and a shear-governed one, say), each a ratio
// where the load ratio crosses the target's. A coarse scan puts a point on every kScanStep of
// F_s0/F_r0 over the bounds that the history leaves empty; each crossing away from the best point
// is then found by regula falsi on the ratio (kRootIterations at most), at the scale fitted from
// the bracketing points.
constexpr double kScanStep = 3.0;
constexpr int kRootIterations = 4;

struct Branches {
  std::vector<EvaluationRecord> found;  // a member of each branch but the best point's
  bool complete = false;                // every scan point and every crossing evaluated
};

Branches other_branches(Ledger& ledger, const CalibrationCampaign& c, double degree,
                        const EvaluationRecord& best, int budget) {
  const LogBox box = log_box(c);
  const Range sr = s_range(box);
  const PeakLoads& t = ledger.targets();
  auto successful = [&] {
    std::vector<EvaluationRecord> out;
    for (const EvaluationRecord& r : ledger.history())
      if (r.loads) out.push_back(r);
    std::sort(out.begin(), out.end(), [](const EvaluationRecord& a, const EvaluationRecord& b) {
      return ratio_coords(a.point).s < ratio_coords(b.point).s;
    });
    return out;
  };
  auto evaluate = [&](double s, double m) -> std::optional<EvaluationRecord> {
    if (budget <= 0 || ledger.remaining() <= 0) return std::nullopt;
    --budget;
    return ledger.evaluate_one(point_from_ratio_coords({s, clamp_to(m, m_range(box, s))}), "scan");
  };
  const double grid = std::log(kScanStep);
  const int cells = std::max(1, int(std::ceil((sr.hi - sr.lo) / grid)));
  for (int j = 0; j <= cells; ++j) {
    const double s = sr.lo + (sr.hi - sr.lo) * j / cells;
    const std::vector<EvaluationRecord> known = successful();
    if (known.empty()) break;
    const EvaluationRecord* nearest = &known.front();
    for (const EvaluationRecord& r : known)
      if (std::abs(ratio_coords(r.point).s - s) < std::abs(ratio_coords(nearest->point).s - s))
        nearest = &r;
    if (std::abs(ratio_coords(nearest->point).s - s) < 0.5 * grid) continue;
    if (!evaluate(s, fitted_m(*nearest, ledger, degree))) return {};
  }
  Branches out;
  out.complete = true;
  const std::vector<EvaluationRecord> known = successful();
  // The best point's own branch: the ratios its trace found consistent, and a scan cell either
  // side.
  Range own{ratio_coords(best.point).s, ratio_coords(best.point).s};
  for (const EvaluationRecord& r : known) {
    if (!r.within_tolerance) continue;
    own.lo = std::min(own.lo, ratio_coords(r.point).s);
    own.hi = std::max(own.hi, ratio_coords(r.point).s);
  }
  for (std::size_t i = 0; i + 1 < known.size(); ++i) {
    EvaluationRecord a = known[i], b = known[i + 1];
    double ga = ratio_gap(a, t), gb = ratio_gap(b, t);
    if (ga * gb >= 0) continue;
    const double sa = ratio_coords(a.point).s, sb = ratio_coords(b.point).s;
    if (sb >= own.lo - grid && sa <= own.hi + grid) continue;
    for (int it = 0; it < kRootIterations; ++it) {
      const double s_a = ratio_coords(a.point).s, s_b = ratio_coords(b.point).s;
      const double s = s_a - ga * (s_b - s_a) / (gb - ga);
      const double w = (s - s_a) / (s_b - s_a);
      const double m = (1 - w) * fitted_m(a, ledger, degree) + w * fitted_m(b, ledger, degree);
      std::optional<EvaluationRecord> r = evaluate(s, m);
      if (r && r->loads && !r->within_tolerance &&
          std::abs(ratio_gap(*r, t)) < std::log1p(c.tolerance))
        r = evaluate(s, fitted_m(*r, ledger, degree));  // the ratio is right: fit the scale
      if (!r || !r->loads) {
        out.complete = false;
        break;
      }
      if (r->within_tolerance) {
        out.found.push_back(*r);
        break;
      }
      const double g = ratio_gap(*r, t);
      if (g * ga < 0) {
        b = *r, gb = g;
      } else {
        a = *r, ga = g;
      }
    }
  }
  return out;
}

double relative_half_width(const Range& r) {
  return (r.hi - r.lo) / (r.hi + r.lo);
}

bool closed(TraceEnd end) {
  return end == TraceEnd::missed || end == TraceEnd::bounds;
}

}  // namespace

ValleyTrace trace_valley(Ledger& ledger, const CalibrationCampaign& c, double degree, int budget) {
  ValleyTrace trace;
  const EvaluationRecord* best = ledger.best();
  if (!best || !best->within_tolerance || budget <= 0) return trace;
  const EvaluationRecord start = *best;
  const int before = int(ledger.history().size());
  ledger.extend_beyond_target(budget);
  auto left = [&] { return budget - (int(ledger.history().size()) - before); };
  // The best point's branch first, half the budget each way at most; the scan with what is left;
  // then each further branch, whose ends join the trace's.
  trace.up = walk(ledger, c, start, +1.0, degree, budget / 3);
  trace.down = walk(ledger, c, start, -1.0, degree, budget / 3);
  const Branches others = other_branches(ledger, c, degree, start, left());
  trace.branches = 1 + int(others.found.size());
  trace.scanned = others.complete;
  for (const EvaluationRecord& o : others.found) {
    const TraceEnd up = walk(ledger, c, o, +1.0, degree, left() / 2);
    const TraceEnd down = walk(ledger, c, o, -1.0, degree, left());
    if (!closed(up)) trace.up = up;
    if (!closed(down)) trace.down = down;
  }
  trace.evaluations = int(ledger.history().size()) - before;
  return trace;
}

ConsistentSet consistent_set(const std::vector<EvaluationRecord>& history,
                             const ValleyTrace& trace) {
  ConsistentSet set;
  for (const EvaluationRecord& r : history) {
    if (r.loads && r.within_tolerance) set.points.push_back(r);
  }
  if (set.points.empty()) {
    set.why = "no evaluated point meets both targets";
    return set;
  }
  auto span = [&](auto value) {
    Range out{value(set.points.front()), value(set.points.front())};
    for (const EvaluationRecord& r : set.points) {
      out.lo = std::min(out.lo, value(r));
      out.hi = std::max(out.hi, value(r));
    }
    return out;
  };
  set.fr0 = span([](const EvaluationRecord& r) { return r.point.fr0_n; });
  set.fs0 = span([](const EvaluationRecord& r) { return r.point.fs0_n; });
  set.ratio = span([](const EvaluationRecord& r) { return r.point.fs0_n / r.point.fr0_n; });
  const bool narrow = relative_half_width(set.fr0) <= kUniqueHalfWidth &&
                      relative_half_width(set.fs0) <= kUniqueHalfWidth;
  if (trace.branches > 1) {
    set.why = sentence("%.0f separate ratios F_s0/F_r0 meet both targets", trace.branches) +
              sentence(
                  " (the set spans F_r0 %.4g-%.4g N, F_s0 %.4g-%.4g N): the two loads do not "
                  "pin both strengths",
                  set.fr0.lo, set.fr0.hi, set.fs0.lo, set.fs0.hi);
  } else if (!narrow) {
    set.why = sentence(
        "the consistent points span F_r0 %.4g-%.4g N and F_s0 %.4g-%.4g N: the two loads do not "
        "pin both strengths",
        set.fr0.lo, set.fr0.hi, set.fs0.lo, set.fs0.hi);
  } else if (!closed(trace.up) || !closed(trace.down) || !trace.scanned) {
    set.why = std::string("the valley was not traced to its ends (toward larger F_s0/F_r0: ") +
              to_string(trace.up) + ", smaller: " + to_string(trace.down) +
              (trace.scanned ? "" : "; the other ratios not scanned") +
              "), so other consistent strengths may exist";
  } else {
    set.unique = true;
    set.why = sentence(
        "the consistent points lie within %.3g%% in each strength, a step of F_s0/F_r0 by a factor "
        "%.3g either way misses the targets at the fitted scale (or leaves the bounds), and no "
        "other ratio within the bounds meets them: each strength is pinned to within a factor "
        "%.3g",
        100 * std::max(relative_half_width(set.fr0), relative_half_width(set.fs0)), kRatioStep,
        kRatioStep);
  }
  return set;
}

const char* to_string(TraceEnd end) {
  switch (end) {
    case TraceEnd::not_traced:
      return "not traced";
    case TraceEnd::missed:
      return "missed the targets";
    case TraceEnd::bounds:
      return "reached the bounds";
    case TraceEnd::budget:
      return "out of budget";
    case TraceEnd::failed:
      return "an evaluation failed";
  }
  return "?";
}

}  // namespace rockcal::calibration
