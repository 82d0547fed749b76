#include "engine/json_input.hpp"

#include <set>
#include <string>
#include <vector>

namespace rockcal {
namespace {

using nlohmann::json;

// An open container while parsing: an object's keys so far and the one being read.
struct OpenContainer {
  bool object = false;
  std::set<std::string> keys;
  std::string key;
};

std::string dotted_path(const std::vector<OpenContainer>& open) {
  std::string path;
  for (const auto& c : open)
    if (c.object) path += (path.empty() ? "" : ".") + c.key;
  return path;
}

template <class Input>
json parse_limited(Input&& input) {
  std::vector<OpenContainer> open;
  // The callback sees each container start with the number of containers around it, and each key.
  const json::parser_callback_t check = [&open](int depth, json::parse_event_t event,
                                                json& parsed) {
    using E = json::parse_event_t;
    if (event == E::object_start || event == E::array_start) {
      if (depth >= kMaxJsonDepth) {
        throw JsonInputError("JSON nested deeper than " + std::to_string(kMaxJsonDepth) +
                             " levels (the limit)");
      }
      open.push_back({event == E::object_start, {}, {}});
    } else if (event == E::object_end || event == E::array_end) {
      if (!open.empty()) open.pop_back();
    } else if (event == E::key && !open.empty()) {
      OpenContainer& object = open.back();
      object.key = parsed.get<std::string>();
      if (!object.keys.insert(object.key).second) {
        const std::string path = dotted_path(open);
        throw JsonInputError(path + ": given more than once", path);
      }
    }
    return true;
  };
  try {
    return json::parse(std::forward<Input>(input), check);
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
