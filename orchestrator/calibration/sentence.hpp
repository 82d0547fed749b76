// Reasons in the report are sentences with numbers in them: one printf-style formatter for the
// calibration's messages (verdicts, the consistent set's reason, the suggestion's).
#pragma once

#include <cstdio>
#include <string>

namespace rockcal::calibration {

inline std::string sentence(const char* pattern, double a, double b = 0, double c = 0,
                            double d = 0) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, pattern, a, b, c, d);
  return buffer;
}

}  // namespace rockcal::calibration
