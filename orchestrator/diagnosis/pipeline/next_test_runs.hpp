// The next test's one batch (analysis/next_test.hpp), after the verdict: at the base model's
// confirmed fit, the base model and a step of kBudgetStep along each strength (how the menu's tests
// follow the strengths; the dataset's follow the base surfaces), and each effect that needs a mark
// at s = 1, on the dataset's and the menu's conditions. The effects that need one: the two leading
// hypotheses' (the verdict and the runner-up; with no verdict the runner-up and the base model),
// and every effect the calibration observations cannot identify (screened out, or not
// identifiable). Then the base at the fit under each of the budget's variants (other packing
// seeds; for lab data also half the speed and a finer resolution, re-fitted as the budget's is):
// each menu test's numerical budget, measured rather than borrowed. Identical runs are the job
// cache's: the base at the fit is the confirmed run.
#pragma once

#include "orchestrator/diagnosis/analysis/next_test.hpp"
#include "orchestrator/diagnosis/pipeline/campaign.hpp"
#include "orchestrator/diagnosis/pipeline/result.hpp"

namespace rockcal::diagnosis {

// `campaign` with every requested effect (the screened-out ones included); `report` as the
// driver has it after the verdict.
NextTest run_next_test(const DiagnosisCampaign& campaign, const DiagnosisResult& report,
                       Evaluator& evaluator);

// Model points of the batch at most, for the job plan: the base's three, every effect and the
// budget's variants; none without effects.
int next_test_model_points(const DiagnosisCampaign& campaign);

}  // namespace rockcal::diagnosis
