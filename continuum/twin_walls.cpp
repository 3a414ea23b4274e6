#include "continuum/twin_walls.hpp"

namespace twinflow::continuum {

void move_walls_in(ContinuumParameters& c, const std::array<double, 6>& distance,
                   const std::array<double, 3>& scene_box) {
  for (int w = 0; w < 2 * c.dim; ++w) {
    const int d = w / 2, side = w % 2;
    if (distance[w] == 0) continue;
    for (int e = 0; e < c.dim; ++e) c.bin_box[e] = scene_box[e];
    c.box[d] -= distance[w];
    if (side != 0) continue;
    c.bin_lower[d] = -distance[w];
    // what was placed in the scene's frame moves with the twin's origin
    for (auto& slab : c.heat_slabs)
      if (slab.direction == d) slab.lower += c.bin_lower[d], slab.upper += c.bin_lower[d];
    for (auto& point : c.probe_points) point[d] += c.bin_lower[d];
  }
}

} // namespace twinflow::continuum
