#pragma once
// twinflow bench: particle-steps/s of the particle core per integrator, scene, size and thread
// count (or, with Bench/Thermo, the same system's energy drift, temperatures and pressure);
// `settings`: the Bench/... keys (study/bench.cpp lists them).

#include <string>
#include <vector>

#include "study/case.hpp"

namespace twinflow::study {

// `cavity`: the default cavity's particle parameters (cases/heated_cavity_2d.prm, loaded at the
// edge), for Bench/Cavity=N1,...: its walled scene beside the same fluid periodic, at N
// particles in a square box, so that what the walls cost is measured in one run.
int bench(const RunOptions& options, const std::vector<std::string>& settings,
          const particle::ParticleParameters& cavity);

} // namespace twinflow::study
