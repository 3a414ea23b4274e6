#pragma once
// twinflow bench: particle-steps/s of the particle core per integrator, scene, size and thread
// count (or, with Bench/Thermo, the same system's energy drift, temperatures and pressure);
// `settings`: the Bench/... keys (study/bench.cpp lists them).

#include <string>
#include <vector>

#include "study/case.hpp"

namespace twinflow::study {

int bench(const RunOptions& options, const std::vector<std::string>& settings);

} // namespace twinflow::study
