// JSON text from outside the process (job files, HTTP bodies, dataset cells), parsed with a nesting
// limit. nlohmann::json parses and destroys deep documents without recursion, but copies, dumps
// and comparisons recurse once per level: a document nested 60,000 levels deep overflows a
// thread's stack in any of them. Refusing it at parse time keeps every later step safe.
#pragma once

#include <istream>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace rockcal {

// Deepest nesting of arrays and objects accepted: `{}` is 1 level, `{"a": [1]}` 2. A job spec
// needs 3 and a campaign request 5; the limit leaves room for any honest document.
inline constexpr int kMaxJsonDepth = 64;

// Malformed JSON (syntax, invalid UTF-8, a number that overflows a double), JSON nested deeper
// than kMaxJsonDepth, or an object that names a key twice (which of the two values counts is
// nowhere written down). The message says which: "malformed JSON: ...", "JSON nested deeper than
// 64 levels (the limit)" or "job.bond.fr0: given more than once"; `field` is the duplicate key's
// dotted path (keys of the enclosing objects; array positions are left out), else empty.
struct JsonInputError : std::runtime_error {
  std::string field;
  explicit JsonInputError(const std::string& message, std::string field_path = "")
      : std::runtime_error(message), field(std::move(field_path)) {}
};

// Parses one JSON document with the nesting limit; throws JsonInputError.
nlohmann::json parse_json_input(std::string_view text);
nlohmann::json parse_json_input(std::istream& in);

}  // namespace rockcal
