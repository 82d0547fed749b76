// A stop asked of the whole process: SIGTERM or SIGINT to rockcal-dem. The time-step loops poll
// process_stop_requested through RunHooks::stop and end the run keeping its curve. While a set-up
// stage runs (a SetupStage is alive: building the packing, bonds, neighbour lists) there is nothing
// a stop could keep, and those stages take seconds to minutes for large specimens: rockcal-dem's
// handler then exits at once. So a stop is honoured at any stage of a run.
#pragma once

#include <atomic>

namespace rockcal {

// Both are read by a signal handler: lock-free and constant-initialised.
inline std::atomic<bool> process_stop_requested{false};
inline std::atomic<int> setup_stages{0};

struct SetupStage {
  SetupStage() { ++setup_stages; }
  ~SetupStage() { --setup_stages; }
  SetupStage(const SetupStage&) = delete;
  SetupStage& operator=(const SetupStage&) = delete;
};

}  // namespace rockcal
