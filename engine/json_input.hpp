// JSON text from outside the process (job files, HTTP bodies, dataset cells), parsed with a nesting
// limit. nlohmann::json parses and destroys deep documents without recursion, but copies, dumps
// and comparisons recurse once per level: a document nested 60,000 levels deep overflows a
// thread's stack in any of them. Refusing it at parse time keeps every later step safe.
#pragma once

#include <istream>
#include <stdexcept>
#include <string_view>

#include <nlohmann/json.hpp>

namespace rockcal {

// Deepest nesting of arrays and objects accepted: `{}` is 1 level, `{"a": [1]}` 2. A job spec
// needs 3 and a campaign request 5; the limit leaves room for any honest document.
inline constexpr int kMaxJsonDepth = 64;

// Malformed JSON (syntax, invalid UTF-8, a number that overflows a double) or JSON nested deeper
// than kMaxJsonDepth. The message says which: "malformed JSON: ..." or "JSON nested deeper than
// 64 levels (the limit)".
struct JsonInputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Parses one JSON document with the nesting limit; throws JsonInputError.
nlohmann::json parse_json_input(std::string_view text);
nlohmann::json parse_json_input(std::istream& in);

}  // namespace rockcal
