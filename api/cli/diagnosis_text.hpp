// A diagnosis's summary as text: what `rockcal diagnose` prints at the end and `rockcal status`
// shows for a diagnosis that has ended.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace rockcal::api {

// The verdict, the gap and the candidates of a diagnosis summary as plain-text tables.
std::string diagnosis_text(const nlohmann::json& summary);

}  // namespace rockcal::api
