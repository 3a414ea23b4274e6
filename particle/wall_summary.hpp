#pragma once
// Reading a wall's results back from a particle run's summary ("walls": {"x_lower": {...}}).

#include <algorithm>
#include <cmath>
#include <string>

#include "io/json.hpp"
#include "statistics/blocking.hpp"

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

// The heat flow across the pair of walls normal to `axis` (0, 1, 2), from the lower wall to
// the upper one, and its error. From the run's one series across the pair ("wall_pairs"); runs
// from before it: the two walls' means, their errors added in quadrature (as if independent,
// which understates it when the walls' flows rise and fall together).
inline statistics::Estimate wall_pair_heat_flux(const io::Json& results, int axis) {
  const std::string axis_name(1, "xyz"[axis]);
  if (const io::Json* pair = io::find(results, {"wall_pairs", axis_name}))
    return {io::number(*pair, {"heat_flux"}), io::number(*pair, {"heat_flux_stderr"})};
  const std::string lo = axis_name + "_lower", up = axis_name + "_upper";
  return {0.5 * (io::number(results, {"walls", lo, "heat_flux_in"}) -
                 io::number(results, {"walls", up, "heat_flux_in"})),
          0.5 * std::hypot(wall_heat_flux_stderr(results, lo), wall_heat_flux_stderr(results, up))};
}

} // namespace twinflow::particle
