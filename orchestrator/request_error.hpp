// A request the service refuses: every campaign kind, dataset and job template reports its refusals
// as this one type, naming the offending field ("bounds.fr0", "dataset.observations[2].value") so
// a client can point at it.
#pragma once

#include <stdexcept>
#include <string>

namespace rockcal::orch {

struct RequestError : std::runtime_error {
  std::string field;    // dotted path of the offending key; empty for the request as a whole
  std::string message;  // what() without the "field: " prefix (what() stops at a NUL in a key)
  RequestError(std::string field_path, const std::string& text)
      : std::runtime_error(field_path.empty() ? text : field_path + ": " + text),
        field(std::move(field_path)),
        message(text) {}
};

// The same refusal with its field placed under `prefix`: a dataset's "observations[2].value" is
// the request's "dataset.observations[2].value". Takes the engine's SpecError too (same fields);
// a field already under the prefix is kept.
template <class Error>
RequestError under(const std::string& prefix, const Error& e) {
  if (prefix.empty()) return RequestError(e.field, e.message);
  if (e.field.empty()) return RequestError(prefix, e.message);
  if (e.field.rfind(prefix + ".", 0) == 0) return RequestError(e.field, e.message);
  return RequestError(prefix + "." + e.field, e.message);
}

}  // namespace rockcal::orch
