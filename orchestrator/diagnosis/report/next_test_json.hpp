// The report's "next_test" block (analysis/next_test.hpp): the menu with each test's noise
// (budget measured or borrowed), the test that best separates the two leading hypotheses and each
// effect the calibration cannot identify, with their conditions in the dataset's units, their
// expected discrimination in noise units and the runs behind them, and the sentence the CLI and the
// page print.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "orchestrator/diagnosis/pipeline/campaign.hpp"
#include "orchestrator/diagnosis/pipeline/result.hpp"

namespace rockcal::diagnosis {

// `fit_on_bounds`: the base model's fitted coordinates that sit on the search box (on_bounds):
// the marks are measured at a fit that is the bound, their strengths' re-fit extrapolating past
// it, which the block says ("fit_on_bounds" and a sentence).
nlohmann::json next_test_json(const NextTest& next, const DiagnosisCampaign& campaign,
                              const std::vector<std::string>& fit_on_bounds = {});

}  // namespace rockcal::diagnosis
