#pragma once
// The twin's walls inside the scene's wall planes (a calibrated twin at the particle walls'
// effective positions): its domain is the scene's box less the distances, while its output
// bins, heat slabs and probe points stay in the scene's frame.

#include <array>

#include "continuum/parameters.hpp"

namespace twinflow::continuum {

// `distance`: per wall in the order x lower, x upper, y lower, ... (0: at the scene's plane).
// Call once, on parameters whose walls are at the scene's planes.
void move_walls_in(ContinuumParameters& c, const std::array<double, 6>& distance,
                   const std::array<double, 3>& scene_box);

} // namespace twinflow::continuum
