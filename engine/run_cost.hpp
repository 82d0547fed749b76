// What a job costs before it runs: its time steps, estimated from the spec alone, so that no
// accepted job can hold a worker for hours by accident (spec.cpp refuses one over kMaxSteps).
#pragma once

namespace rockcal {

struct JobSpec;

// The time step a run of the (effective) spec takes: loading.dt, or dt_safety x the critical step
// of its smallest grain.
double run_time_step(const JobSpec& run);

// The time steps of all the job's runs: the platen travel (max_strain x the loaded length) at the
// slowest speed of two-rate loading (slow_factor x the platen speed) as if the whole travel ran at
// it, plus the elastic-wave transits of the ramps, holds and confinement; a rate study adds its
// runs at halving speeds from half the job's (its probe may pick a slower start, which this does
// not foresee); each run at most loading.max_steps. +inf when it overflows.
double estimated_steps(const JobSpec& run);

// The speed of a compression wave along the specimen (loaded length / transit time), m/s.
double wave_speed(const JobSpec& run);

}  // namespace rockcal
