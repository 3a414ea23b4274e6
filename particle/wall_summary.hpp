#pragma once
// Reading a wall's results back from a particle run's summary ("walls": {"x_lower": {...}}).

#include <algorithm>
#include <string>

#include "io/json.hpp"

namespace twinflow::particle {

// A wall's heat-flux error: the largest over its blockings (1, 2 and 4 blocks merged; a roll
// slower than a block makes the finest one too small); runs from before the blockings were
// recorded: the one error they have.
inline double wall_heat_flux_stderr(const io::Json& results, const std::string& wall) {
  double e = io::number(results, {"walls", wall, "heat_flux_in_stderr"});
  if (const io::Json* b = io::find(results, {"walls", wall, "heat_flux_in_stderr_blocking"}))
    for (const auto& x : *b) e = std::max(e, x.get<double>());
  return e;
}

} // namespace twinflow::particle
