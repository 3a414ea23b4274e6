#include "particle/parameters.hpp"

#include <algorithm>
#include <cmath>

namespace twinflow::particle {

double ParticleParameters::largest_cutoff() const {
  double rc = dissipation.cutoff;
  if (conservative != ConservativeForce::None) rc = std::max(rc, conservative_cutoff);
  if (heat != HeatLaw::None && energy == EnergyModel::Dpde) rc = std::max(rc, heat_weight.cutoff);
  return rc; // wall range is per particle, not a pair cutoff
}

bool ParticleParameters::has_walls() const {
  for (int d = 0; d < dim; ++d)
    if (walls[d].present) return true;
  return false;
}

bool ParticleParameters::has_wall_model(WallModel m) const {
  for (int d = 0; d < dim; ++d)
    for (int side = 0; side < 2; ++side)
      if (walls[d].present && walls[d].model[side] == m) return true;
  return false;
}

double ParticleParameters::wall_material_density() const {
  return wall_density > 0 ? wall_density : density;
}

long ParticleParameters::particle_count() const {
  double volume = box[0] * box[1];
  if (dim == 3) volume *= box[2];
  return std::lround(density * volume);
}

const char* to_string(Integrator i) {
  switch (i) {
  case Integrator::Euler:
    return "euler";
  case Integrator::EcVerlet:
    return "ec-verlet";
  case Integrator::Shardlow:
    return "shardlow";
  }
  return "?";
}

} // namespace twinflow::particle
