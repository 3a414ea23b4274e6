#include "study/twin_wall_theory.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "continuum/twin_walls.hpp"
#include "particle/theory.hpp"
#include "transport/estimates.hpp"
#include "transport/wall_layer.hpp"

namespace twinflow::study {

namespace {
// The twin's walls over pinned layers moved in by their depths (from the scene's planes; its
// Navier slips, measured from the planes, then reach that much further beyond the twin's walls),
// and the particles of those layers, at the walls' densities, left out of the twin's count.
void place_pinned_walls(const CaseParameters& c, continuum::ContinuumParameters& twin,
                        const std::array<double, 6>& depth, const std::array<double, 6>& density) {
  std::array<double, 6> distance = continuum::moved_wall_distances(twin);
  for (int w = 0; w < 2 * twin.dim; ++w) {
    continuum::DirectionBoundary& b = twin.boundary[w / 2];
    const double moved = depth[w] - b.pinned_depth[w % 2];
    if (b.slip_length[w % 2] > 0) b.slip_length[w % 2] += moved;
    distance[w] += moved;
    b.pinned_depth[w % 2] = depth[w];
  }
  continuum::move_walls_in(twin, distance, c.scene.box);
  double outside = 0;
  for (int w = 0; w < 2 * twin.dim; ++w) {
    double area = 1;
    for (int e = 0; e < twin.dim; ++e) area *= e == w / 2 ? 1.0 : twin.box[e];
    outside += density[w] * depth[w] * area;
  }
  twin.particle_count =
      outside > 0 ? static_cast<double>(c.particle.particle_count()) - outside : 0.0;
}
} // namespace

int take_wall_jumps(const CaseParameters& c, const transport::Coefficients& k,
                    continuum::ContinuumParameters& twin, const WallValues* at_walls) {
  const particle::ParticleParameters& p = c.particle;
  const int heated = c.scene.heated_direction();
  if (heated < 0 || !std::isfinite(k.diffusion) || !(k.state_temperature > 0)) return 0;
  int taken = 0;
  std::array<double, 6> depth{}, density{}; // of pinned layers, per wall
  for (int d = 0; d < c.scene.dim; ++d) {
    const auto& walls = p.walls[d];
    if (!walls.present) continue;
    for (int side = 0; side < 2; ++side) {
      if (!walls.thermal[side] || walls.model[side] != particle::WallModel::HalfSpace) continue;
      const double T_w = walls.temperature[side];
      const double given = at_walls ? (*at_walls)[d][side] : std::nan("");
      const double n = given > 0 ? given : c.scene.density_on_isobar(T_w);
      transport::WallLayerInput in;
      in.dim = p.dim;
      in.density = n, in.temperature = T_w;
      in.kappa =
          twin.conductivity.at(n, T_w, twin.number_density, twin.reference_temperature).value;
      // the pair part's theory: rho^2 lambda(T) / (2d) int r^2 g w_H, scaled from the state point
      const double lambda = transport::pair_conductance(p, T_w);
      const double lambda_state = transport::pair_conductance(p, k.state_temperature);
      in.kappa_pair = lambda_state > 0 ? k.conductivity_pair * std::pow(n / k.state_density, 2) *
                                             lambda / lambda_state
                                       : 0.0;
      const double a_D = std::isfinite(k.diffusion_exponent) ? k.diffusion_exponent : 2.0;
      in.diffusion = k.diffusion * std::pow(T_w / k.state_temperature, a_D) * k.state_density / n;
      in.pair_conductance = lambda;
      in.heat_capacity = p.cv;
      in.heat_weight = p.heat_weight, in.friction_weight = p.dissipation;
      in.wall_density = p.wall_material_density();
      in.wall_factor = walls.conduction[side];
      in.gamma = particle::pair_friction(p, T_w);
      in.no_slip = walls.no_slip;
      const transport::WallLayer layer = transport::solve_wall_layer(in);
      std::printf("continuum: %s wall from the wall model (n %.3g, T %.3g, f %.3g): extrapolation "
                  "length %.3f rc, %s %.4g\n",
                  scene::wall_name(d, side).c_str(), n, T_w, in.wall_factor,
                  layer.extrapolation_length,
                  layer.extrapolation_length < 0 ? "a pinned layer: the twin's wall moved in by"
                                                 : "Kapitza conductance",
                  layer.extrapolation_length < 0 ? -layer.extrapolation_length : layer.conductance);
      // A pinned layer (b < 0): the bulk reaches T_w |b| inside the fluid, which the twin's
      // wall moved in by |b| gives (a negative Robin conductance instead made the steady
      // problem lose its solution: the default cavity's twin met a fold at Ra 1326 of 1359,
      // docs/notebook/2026-11-27-predictions-from-measurements-without-walls.md).
      const bool pinned = layer.extrapolation_length < -1e-3;
      depth[2 * d + side] = pinned ? -layer.extrapolation_length : 0.0;
      density[2 * d + side] = n;
      const bool jump = layer.extrapolation_length >= 1e-3;
      twin.boundary[d].kapitza_conductance[side] = jump ? layer.conductance : 0.0;
      twin.boundary[d].kapitza_inverse = false;
      taken += jump || pinned;
    }
  }
  place_pinned_walls(c, twin, depth, density);
  return taken;
}

int take_wall_slips(const CaseParameters& c, continuum::ContinuumParameters& twin,
                    const WallValues* at_walls, const WallValues* temperatures) {
  if (!continuum::has_robin_walls(twin.model)) return 0; // no flow, or no Navier walls
  const particle::ParticleParameters& p = c.particle;
  int taken = 0;
  for (int d = 0; d < c.scene.dim; ++d) {
    const auto& walls = p.walls[d];
    auto& b = twin.boundary[d];
    if (!walls.present || !walls.no_slip || b.periodic || !b.no_slip) continue;
    for (int side = 0; side < 2; ++side) {
      if (walls.model[side] != particle::WallModel::HalfSpace) continue;
      const double own_T = temperatures ? (*temperatures)[d][side] : std::nan("");
      const double T = walls.thermal[side] ? walls.temperature[side]
                       : own_T > 0         ? own_T
                                           : c.scene.temperature;
      const double given = at_walls ? (*at_walls)[d][side] : std::nan("");
      const double n = given > 0 ? given : c.scene.density_on_isobar(T);
      transport::SlipLayerInput in;
      in.dim = p.dim, in.density = n, in.temperature = T, in.mass = p.mass;
      in.viscosity = twin.viscosity.at(n, T, twin.number_density, twin.reference_temperature).value;
      in.gamma = particle::pair_friction(p, T);
      in.wall_gamma = in.gamma;
      in.wall_density = p.wall_material_density();
      in.friction_weight = p.dissipation;
      in.diffuse = walls.thermal[side] && p.wall_diffuse;
      const transport::SlipLayer layer = transport::solve_slip_layer(in);
      std::printf("continuum: %s wall's slip from the wall model (n %.3g, T %.3g, %s): %.3f rc\n",
                  scene::wall_name(d, side).c_str(), n, T, in.diffuse ? "diffuse" : "bounce-back",
                  layer.slip_length);
      b.kinetic_slip[side] = false;
      // from the scene's plane: beyond a wall moved in over a pinned layer by that much more
      b.slip_length[side] =
          layer.slip_length > 1e-3 ? layer.slip_length + b.pinned_depth[side] : 0.0;
      taken += b.slip_length[side] > 0;
    }
  }
  return taken;
}

WallValues wall_values(const continuum::BinAverages& bins, int dim, const std::string& name) {
  WallValues out;
  for (auto& sides : out) sides = {{std::nan(""), std::nan("")}};
  const auto field = std::find(bins.names.begin(), bins.names.end(), name);
  if (field == bins.names.end()) return out;
  const std::vector<double>& n =
      bins.own_values()[static_cast<std::size_t>(field - bins.names.begin())];
  const auto& count = bins.bins;
  for (int d = 0; d < dim; ++d)
    for (int side = 0; side < 2; ++side) {
      double layer[2] = {0, 0}, in_layer[2] = {0, 0};
      for (std::size_t b = 0; b < n.size(); ++b) {
        std::size_t index = b; // bin b's index along d (x fastest)
        for (int e = 0; e < d; ++e) index /= count[e];
        index %= count[d];
        const std::size_t from_wall = side ? count[d] - 1 - index : index;
        if (from_wall < 2) layer[from_wall] += n[b], in_layer[from_wall] += 1;
      }
      const double first = layer[0] / in_layer[0];
      out[d][side] = in_layer[1] > 0 ? 1.5 * first - 0.5 * layer[1] / in_layer[1] : first;
    }
  return out;
}

} // namespace twinflow::study
