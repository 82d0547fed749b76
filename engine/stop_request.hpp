// A stop asked of the whole process: SIGTERM or SIGINT to rockcal-dem set it. The time-step loops
// poll it through RunHooks::stop; the set-up stages that can take long before them (building a
// packing) call throw_if_stop_requested(), so that a stop is honoured at any stage of a run.
#pragma once

#include <atomic>
#include <stdexcept>

namespace rockcal {

// Set from a signal handler: lock-free and constant-initialised.
inline std::atomic<bool> process_stop_requested{false};

struct StopRequested : std::runtime_error {
  StopRequested() : std::runtime_error("stopped on request (SIGTERM or SIGINT)") {}
};

inline void throw_if_stop_requested() {
  if (process_stop_requested.load(std::memory_order_relaxed)) throw StopRequested();
}

}  // namespace rockcal
