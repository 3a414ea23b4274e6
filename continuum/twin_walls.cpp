#include "continuum/twin_walls.hpp"

namespace twinflow::continuum {

void move_walls_in(ContinuumParameters& c, const std::array<double, 6>& distance,
                   const std::array<double, 3>& scene_box) {
  bool moved = c.bin_box[0] > 0; // an earlier call's distances are replaced
  for (int w = 0; w < 2 * c.dim; ++w) moved |= distance[w] != 0;
  if (!moved) return;
  for (int d = 0; d < c.dim; ++d) {
    const double shift = -distance[2 * d] - c.bin_lower[d]; // the origin's move since the last call
    c.box[d] = scene_box[d] - distance[2 * d] - distance[2 * d + 1];
    c.bin_lower[d] = -distance[2 * d];
    c.bin_box[d] = scene_box[d];
    // what was placed in the scene's frame moves with the twin's origin
    for (auto& slab : c.heat_slabs)
      if (slab.direction == d) slab.lower += shift, slab.upper += shift;
    for (auto& point : c.probe_points) point[d] += shift;
  }
}

std::array<double, 6> moved_wall_distances(const ContinuumParameters& c) {
  std::array<double, 6> distance{};
  if (c.bin_box[0] > 0)
    for (int d = 0; d < c.dim; ++d) {
      distance[2 * d] = -c.bin_lower[d];
      distance[2 * d + 1] = c.bin_box[d] - c.box[d] + c.bin_lower[d];
    }
  return distance;
}

} // namespace twinflow::continuum
