#pragma once
// The twin's walls inside the scene's wall planes (a calibrated twin at the particle walls'
// effective positions): its domain is the scene's box less the distances, while its output
// bins, heat slabs and probe points stay in the scene's frame.

#include <array>

#include "continuum/parameters.hpp"

namespace twinflow::continuum {

// `distance`: per wall in the order x lower, x upper, y lower, ... (0: at the scene's plane),
// measured from the scene's planes: a later call replaces an earlier one's.
void move_walls_in(ContinuumParameters& c, const std::array<double, 6>& distance,
                   const std::array<double, 3>& scene_box);
// The distances move_walls_in last set (all 0 for walls at the scene's planes).
std::array<double, 6> moved_wall_distances(const ContinuumParameters& c);

} // namespace twinflow::continuum
