#include "engine/json_input.hpp"

#include <string>

namespace rockcal {
namespace {

using nlohmann::json;

template <class Input>
json parse_limited(Input&& input) {
  // The callback sees each container start with the number of containers around it.
  const json::parser_callback_t limit = [](int depth, json::parse_event_t event, json&) {
    const bool opens =
        event == json::parse_event_t::object_start || event == json::parse_event_t::array_start;
    if (opens && depth >= kMaxJsonDepth) {
      throw JsonInputError("JSON nested deeper than " + std::to_string(kMaxJsonDepth) +
                           " levels (the limit)");
    }
    return true;
  };
  try {
    return json::parse(std::forward<Input>(input), limit);
  } catch (const json::exception& e) {  // parse_error, or out_of_range for 1e999
    throw JsonInputError(std::string("malformed JSON: ") + e.what());
  }
}

}  // namespace

json parse_json_input(std::string_view text) {
  return parse_limited(text);
}

json parse_json_input(std::istream& in) {
  return parse_limited(in);
}

}  // namespace rockcal
