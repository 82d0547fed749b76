// How far a model misses the lab, observation by observation, in the terms the report shows:
// each charged residual ln(sim / lab) (gap.hpp) against its own noise sqrt(budget^2 + sigma^2 +
// fit^2), fit being the spread the calibration leaves in a held-out prediction (fit_spread.hpp),
// the scale rms_in_budgets and the verdict rule use. The verdict quotes it when it cannot judge
// (undetermined) and when a miss is left that it does not explain (verdict.hpp, temper_verdict).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/observations.hpp"

namespace rockcal::diagnosis {

struct ObservationMiss {
  std::string id;
  Role role = Role::calibration;
  double residual = 0.0;  // charged ln(sim / lab): the report's observations[].base.charged
  double budget = 0.0;    // numerical budget: observations[].budget
  double sigma = 0.0;     // lab uncertainty / value: observations[].lab_uncertainty
  double fit = 0.0;       // sd the fit leaves in the prediction: observations[].base.fit_spread
  double noise() const;   // sqrt(budget^2 + sigma^2 + fit^2)
  double in_budgets() const;
};

struct ModelMiss {
  std::string model;  // "the base model", "the model with rate"
  // rms in budgets (rms_in_budgets) over each role's observations; nullopt where none has a
  // residual.
  std::optional<double> calibration, held_out;
  // The observations beyond `beyond` noise budgets (the decision rule's gap_budgets), in dataset
  // order; and the one furthest out, to quote when none is beyond.
  std::vector<ObservationMiss> beyond;
  std::optional<ObservationMiss> largest;
};

// `residuals` are ln(sim / lab) of the model's real runs (NaN where a run failed);
// `fit_variance` the fit's spread per target (held_out_fit_variance, verdict.hpp; empty: none).
ModelMiss model_miss(std::string model, const std::vector<Target>& targets,
                     const std::vector<double>& residuals, const std::vector<double>& budget,
                     const std::vector<double>& fit_variance, double beyond);

// Whether the rms of either role exceeds `limit` budgets.
bool misses_beyond(const ModelMiss& m, double limit);

// "the base model misses uct-1 (calibration) by -0.93 in ln (61% below the lab), 8.3 times its
// noise 0.112 (budget 0.100, lab uncertainty 0.050[, fit spread 0.130]), and ...: rms 5.9 noise
// budgets over the calibration observations"; or, with none beyond, "the base model meets every
// observation within 1.0 noise budgets (the furthest, ..., 0.4 times its noise 0.112 ...): rms
// ...".
std::string miss_text(const ModelMiss& m, double beyond);

}  // namespace rockcal::diagnosis
