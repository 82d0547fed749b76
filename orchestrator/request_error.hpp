// A request the service refuses: names the offending field so a client can point at it.
#pragma once

#include <stdexcept>
#include <string>

namespace rockcal::orch {

struct RequestError : std::runtime_error {
  std::string field;
  RequestError(std::string field_path, const std::string& message)
      : std::runtime_error(message), field(std::move(field_path)) {}
};

}  // namespace rockcal::orch
