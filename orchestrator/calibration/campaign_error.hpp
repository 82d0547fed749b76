// An invalid calibration campaign; `field` is the dotted path of the offending key
// ("bounds.fr0", "job.sample.diameter"), which the API returns as a 400's "field".
#pragma once

#include <stdexcept>
#include <string>

namespace rockcal::calibration {

struct CampaignError : std::runtime_error {
  std::string field;
  CampaignError(std::string field_path, const std::string& message)
      : std::runtime_error(field_path + ": " + message), field(std::move(field_path)) {}
};

}  // namespace rockcal::calibration
