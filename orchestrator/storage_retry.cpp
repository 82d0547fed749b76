#include "orchestrator/storage_retry.hpp"

#include <algorithm>
#include <iostream>
#include <thread>

namespace rockcal::orch {

using Clock = std::chrono::steady_clock;

bool pause_unless_stopped(std::chrono::milliseconds wait, std::stop_token stop) {
  const auto until = Clock::now() + wait;
  while (!stop.stop_requested() && Clock::now() < until)
    std::this_thread::sleep_for(std::min(wait, std::chrono::milliseconds(50)));
  return !stop.stop_requested();
}

bool write_with_retry(db::Store& store, const std::function<void()>& write,
                      const StorageRetry& retry, std::stop_token stop) {
  const auto first_failure = Clock::now();
  for (auto wait = retry.first_wait;; wait = std::min(wait * 2, retry.max_wait)) {
    try {
      write();
      store.note_success();
      return true;
    } catch (const db::SqliteError& e) {
      const std::string kind = store.note_failure(e);
      // In milliseconds: give_up_after may be milliseconds::max(), which nanoseconds overflow.
      const auto waited =
          std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - first_failure);
      if (kind.empty() || waited >= retry.give_up_after) throw;
      if (wait == retry.first_wait)  // once per write, as one line
        std::cerr << "rockcal: storage " + kind + " (" + e.what() + "); retrying\n";
    }
    if (!pause_unless_stopped(wait, stop)) return false;
  }
}

}  // namespace rockcal::orch
