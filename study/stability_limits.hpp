#pragma once
// Stiff choices caught up front: the integrator, time step and scene checked against where the
// measured stability maps saw runs fail (data/stability_limits.csv, the one table), and the
// fluctuation number 000:(3.34) against its stated bound. Warnings, not refusals: each names the
// stable alternative.

#include <filesystem>
#include <string>
#include <vector>

#include "particle/parameters.hpp"

namespace twinflow::study {

struct StabilityLimit {
  std::string integrator, scene; // "euler" / "ec-verlet" / "any"; "thermal walls", ...
  double largest_stable_dt = 0, smallest_failed_dt = 0;
  std::string maps; // which maps, and when
};

// The table (throws io::InputError on a malformed row, naming the file and line).
std::vector<StabilityLimit> read_stability_limits(const std::filesystem::path& csv);
// A shipped case file's path (cases/NAME.prm of the source tree).
std::filesystem::path shipped_case(const std::string& name);
// The shipped table (data/stability_limits.csv of the source tree).
const std::vector<StabilityLimit>& stability_limits();

// One line per stiff or biased choice of `p` (empty: none): a time step beyond the stability
// maps, a large fluctuation number, a per-particle energy offset with a pair force between walls.
std::vector<std::string> stiff_choice_warnings(const particle::ParticleParameters& p,
                                               const std::vector<StabilityLimit>& limits);

} // namespace twinflow::study
