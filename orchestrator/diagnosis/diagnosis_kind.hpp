// The campaign kind "diagnosis" for the service (listed in orchestrator/all_kinds.cpp). Its plan
// validates the whole request (400 naming the field) and creates no jobs up front; its driver
// thread runs the diagnosis on the pool and returns the report JSON (the campaign summary); its
// report_html renders that summary as a page.
#pragma once

#include "orchestrator/campaign_kinds.hpp"
#include "orchestrator/diagnosis/pipeline/campaign.hpp"

namespace rockcal::diagnosis {

orch::CampaignKind diagnosis_kind();

// The most jobs a diagnosis can create: every model point it may run times the distinct runs
// (test and conditions) of its dataset.
std::size_t planned_jobs(const DiagnosisCampaign& c);

}  // namespace rockcal::diagnosis
