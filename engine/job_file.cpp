#include "engine/job_file.hpp"

#include "engine/json_input.hpp"

namespace rockcal {

JobFile read_job(std::istream& in) {
  JobFile out;
  try {
    nlohmann::json j;
    try {
      j = parse_json_input(in);
    } catch (const JsonInputError& e) {
      throw SpecError("(root)", e.what());
    }
    out.spec = parse_job(j);
  } catch (const SpecError& e) {
    out.error = {{"error", e.what()}, {"field", e.field}};
  }
  return out;
}

std::string json_text(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace rockcal
