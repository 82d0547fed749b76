// The campaign kind "diagnosis" for the service (listed in orchestrator/all_kinds.cpp). Its plan
// validates the whole request (400 naming the field) and creates no jobs up front; its driver
// thread runs the diagnosis on the pool and returns the report JSON (the campaign summary); its
// report_html renders that summary as a page.
#pragma once

#include "orchestrator/campaign_kinds.hpp"
#include "orchestrator/diagnosis/pipeline/campaign.hpp"
#include "orchestrator/progress_model.hpp"

namespace rockcal::diagnosis {

orch::CampaignKind diagnosis_kind();

// The most jobs a diagnosis can create, by phase ("grid", "budget", "confirm", and "next_test"
// unless turned off): every model point it may run times the distinct runs (test and conditions)
// of its dataset (the next test's: of its dataset and menu). The budget of its
// progress model (orchestrator/progress_model.hpp, unit "jobs").
std::vector<orch::BudgetPart> planned_job_parts(const DiagnosisCampaign& c);

// The sum of planned_job_parts.
std::size_t planned_jobs(const DiagnosisCampaign& c);

}  // namespace rockcal::diagnosis
