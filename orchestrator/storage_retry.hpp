// Store writes that meet a storage fault (db/storage_faults.hpp: a lock another writer holds, a
// full disk, an I/O error) are tried again with back-off: the one way the worker pool and the
// campaign drivers ride out a passing fault instead of losing a job's outcome or a campaign.
#pragma once

#include <chrono>
#include <functional>
#include <stop_token>

#include "db/store.hpp"

namespace rockcal::orch {

struct StorageRetry {
  std::chrono::milliseconds first_wait{50};  // after the first failed try; doubled after each
  std::chrono::milliseconds max_wait{2000};  // the longest wait between two tries
  // How long after the first failed try a write gives up and throws its fault.
  std::chrono::milliseconds give_up_after = std::chrono::milliseconds::max();
};

// Runs `write`. While it throws a storage fault, records it in the store's health (once per write
// on stderr), waits and tries again. True once a try succeeded; false when `stop` was requested
// first; throws the fault once `give_up_after` has passed, and any other error at once.
bool write_with_retry(db::Store& store, const std::function<void()>& write,
                      const StorageRetry& retry, std::stop_token stop);

// Waits `wait`, or less if `stop` is requested; false when it is.
bool pause_unless_stopped(std::chrono::milliseconds wait, std::stop_token stop);

}  // namespace rockcal::orch
