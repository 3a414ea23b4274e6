#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>

namespace twinflow::scene {

bool SceneParameters::has_walls() const {
  for (int d = 0; d < dim; ++d)
    if (!boundary[d].periodic) return true;
  return false;
}

int SceneParameters::heated_direction() const {
  for (int d = 0; d < dim; ++d) {
    const auto& b = boundary[d];
    if (!b.periodic && b.thermal[0] && b.thermal[1] && b.temperature[0] != b.temperature[1])
      return d;
  }
  return -1;
}

double SceneParameters::thermal_wall_epsilon() const {
  double lo = HUGE_VAL, hi = 0;
  for (int d = 0; d < dim; ++d)
    for (int side = 0; side < 2; ++side)
      if (!boundary[d].periodic && boundary[d].thermal[side]) {
        lo = std::min(lo, boundary[d].temperature[side]);
        hi = std::max(hi, boundary[d].temperature[side]);
      }
  return hi > 0 ? (hi - lo) / (hi + lo) : 0;
}

double SceneParameters::thermal_wall_mean() const {
  double sum = 0;
  int walls = 0;
  for (int d = 0; d < dim; ++d)
    if (!boundary[d].periodic)
      for (int side = 0; side < 2; ++side)
        if (boundary[d].thermal[side]) sum += boundary[d].temperature[side], ++walls;
  return walls > 0 ? sum / walls : 0;
}

double SceneParameters::density_on_isobar(double T) const {
  const int heated = heated_direction();
  if (heated < 0) return density;
  const auto& t = boundary[heated].temperature;
  const double hot = std::max(t[0], t[1]), cold = std::min(t[0], t[1]);
  return density * (hot - cold) / std::log(hot / cold) / T; // the ideal gas's p / T
}

double SceneParameters::stratification(double particle_mass) const {
  double g = 0;
  int up = -1;
  for (int d = 0; d < dim; ++d)
    if (std::fabs(gravity[d]) > g) g = std::fabs(gravity[d]), up = d;
  if (up < 0) return 0;
  const double T = thermal_wall_mean() > 0 ? thermal_wall_mean() : temperature;
  return g * box[up] * particle_mass / T; // g H / c^2, c^2 = k T / m, k = 1 (docs/theory.md)
}

std::string wall_name(int direction, int side) {
  return std::string(1, "xyz"[direction]) + (side ? "_upper" : "_lower");
}

} // namespace twinflow::scene
