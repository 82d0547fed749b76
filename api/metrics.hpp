// /metrics in the Prometheus text format: jobs by state, queue length, job durations.
#pragma once

#include <string>

#include "db/store.hpp"

namespace rockcal::api {

std::string metrics_text(db::Store& store, int workers);

}  // namespace rockcal::api
