// An invalid calibration campaign; `field` is the dotted path of the offending key
// ("bounds.fr0", "job.sample.diameter"), which the API returns as a 400's "field".
#pragma once

#include <stdexcept>
#include <string>

namespace rockcal::calibration {

struct CampaignError : std::runtime_error {
  std::string field;
  std::string message;  // what() without the "field: " prefix (what() stops at a NUL in a key)
  CampaignError(std::string field_path, const std::string& text)
      : std::runtime_error(field_path + ": " + text), field(std::move(field_path)), message(text) {}
};

}  // namespace rockcal::calibration
