// Test drivers: each sets up the loading of a specimen, runs it and reduces the result.
#pragma once

#include "engine/loadtests/result.hpp"

namespace rockcal {

// UCT (cylinder along its axis) and BTT (disc across a diameter, loaded by its btt_geometry): the
// platens seat the specimen (loadtests/seating.hpp), then close at the job's speed until the load
// has fallen past a peak with failure (loadtests/peak.hpp), or the strain or step limit. Triaxial:
// the UCT cylinder, first confined by loading.confining_pressure on its lateral surface (ramped in
// with the platens still), then loaded like the UCT; the peak load is the axial platen load. Every
// driver runs the job's effective spec (effective_spec(): the effects' spec hooks applied).
TestResult run_compression_test(const JobSpec& spec, const RunHooks& hooks);

// Counts the breaks by mode and (BTT) where the disc broke first, from r.breaks: after a run, and
// again once a decomposed run has gathered every rank's breaks.
void tally_breaks(const JobSpec& spec, TestResult& r);

// Elastic test: the UCT specimen compressed by a small strain and relaxed; E and nu from the
// stress and strain measured in the interior, away from the free surface and the platens. Each of
// its two stages loads over kElasticLoadTransits elastic-wave transit times (quasi-static), then
// holds until at rest, for at most kElasticHoldLimitTransits.
constexpr double kElasticLoadTransits = 20.0;
constexpr double kElasticHoldLimitTransits = 400.0;
TestResult run_elastic_test(const JobSpec& spec, const RunHooks& hooks);

// Rate study of a UCT or BTT: the test at a sequence of halving platen speeds, starting where the
// time to peak is kTransitsToPeak elastic-wave transit times; the peak is extrapolated to zero
// speed. Returns the slowest run, with the study attached.
TestResult run_rate_study(const JobSpec& spec, const RunHooks& hooks);

// Fills s.extrapolated_peak_n, rate_error and converged from s.peaks_n (at halving speeds, at
// least two): geometric extrapolation when the last differences shrink, else the last difference.
void extrapolate_to_zero_speed(RateStudy& s);

// Dispatches on spec.test (and loading.rate_study).
TestResult run_test(const JobSpec& spec, const RunHooks& hooks = {});

}  // namespace rockcal
