// A job file read the way rockcal-dem reads it: the validated spec, or the {"error", "field"}
// object it prints before exiting 2. Shared with the tests, so that the fuzz run checks the very
// path (and the very JSON writer) the engine uses.
#pragma once

#include <istream>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/spec.hpp"

namespace rockcal {

struct JobFile {
  std::optional<JobSpec> spec;  // absent when the file is invalid
  nlohmann::json error;         // {"error": message, "field": path} when it is
};

JobFile read_job(std::istream& in);

// Everything rockcal-dem prints is valid JSON whatever bytes the job file held: an error message
// may quote them (a parse error shows the bytes it stopped at), and invalid UTF-8 becomes U+FFFD.
std::string json_text(const nlohmann::json& j);

}  // namespace rockcal
