// The campaign summary (JSON) and the HTML page of a diagnosis campaign, rendered from what the
// pipeline found.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "orchestrator/diagnosis/pipeline/campaign.hpp"
#include "orchestrator/diagnosis/pipeline/result.hpp"

namespace rockcal::diagnosis {

// The campaign summary: model units throughout.
nlohmann::json to_json(const DiagnosisResult& report, const DiagnosisCampaign& campaign);

// A self-contained page (inline SVG, no external assets) of a summary made by to_json.
std::string report_html(const nlohmann::json& summary);

}  // namespace rockcal::diagnosis
