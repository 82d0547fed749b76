// Builds the simulated specimen of a job: packing, bonds, contact law, damping, platens and dt.
#pragma once

#include <mpi.h>

#include "engine/loadtests/result.hpp"
#include "engine/simulation.hpp"
#include "engine/spec.hpp"

namespace rockcal {

// Loading axis is z for every test. Platens touch the top and bottom particles at start. Under MPI
// (`comm` not null, more than one rank) each rank keeps its slab of the specimen.
Simulation make_specimen(const JobSpec& spec, MPI_Comm comm = MPI_COMM_NULL);

// Particle and bond counts over all ranks, into the result.
void count_specimen(const Simulation& sim, TestResult& r);

// Specimen length along the loading axis (H for UCT/elastic, D for BTT), m.
double loaded_length(const JobSpec& spec);

// Volume a particle occupies in the packing (sphere volume / FCC solid fraction), m^3.
double particle_volume(const JobSpec& spec);
// Time for an elastic wave to cross the specimen along the loading axis (FCC lattice modulus), s.
double wave_transit_time(const JobSpec& spec);

// Platen indices in Simulation::walls.
constexpr int kBottomPlaten = 0;
constexpr int kTopPlaten = 1;

}  // namespace rockcal
