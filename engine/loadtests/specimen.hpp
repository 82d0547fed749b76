// Builds the simulated specimen of a job: packing, bonds, contact law, damping, platens and dt.
#pragma once

#include "engine/simulation.hpp"
#include "engine/spec.hpp"

namespace rockcal {

// Loading axis is z for every test. Platens touch the top and bottom particles at start.
Simulation make_specimen(const JobSpec& spec);

// Specimen length along the loading axis (H for UCT/elastic, D for BTT), m.
double loaded_length(const JobSpec& spec);

// Platen indices in Simulation::walls.
constexpr int kBottomPlaten = 0;
constexpr int kTopPlaten = 1;

}  // namespace rockcal
