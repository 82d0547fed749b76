// Wall-clock and progress pacing shared by the test drivers.
#pragma once

#include <chrono>

#include "engine/loadtests/result.hpp"

namespace rockcal {

class RunClock {
 public:
  RunClock(const RunHooks& hooks, double period_s) : hooks_(hooks), period_s_(period_s) {}

  double elapsed_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  bool stop_requested() const {
    return hooks_.stop && hooks_.stop->load(std::memory_order_relaxed);
  }

  // Reports progress when a period has passed since the last report (or when forced).
  template <class MakeProgress>
  void maybe_report(MakeProgress make, bool force = false) {
    if (!hooks_.on_progress) return;
    const double t = elapsed_s();
    if (!force && t - last_report_s_ < period_s_) return;
    last_report_s_ = t;
    hooks_.on_progress(make(t));
  }

 private:
  const RunHooks& hooks_;
  double period_s_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  double last_report_s_ = 0.0;
};

}  // namespace rockcal
