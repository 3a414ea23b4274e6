#include "compare/calibration.hpp"

#include <algorithm>
#include <cmath>

#include "io/files.hpp"
#include "particle/wall_summary.hpp"

namespace twinflow::compare {

std::string calibration_description(const CompareParameters& compare, const TwinFacts& twin) {
  std::string text =
      compare.calibration != "kapitza" || !twin.robin_walls
          ? "walls at the fluid's wall temperatures"
      : twin.kapitza_inverse
          ? "Kapitza walls, inverse law (h_K T_w^2 (1/T_f - 1/T_w) = the particle wall's heat "
            "flux)"
          : "Kapitza walls (h_K = the particle wall's heat flux / its jump)";
  if (compare.wall_slip && twin.robin_walls)
    text += "; Navier slip at no-slip walls (b from the particle wall's friction)";
  if (compare.effective_walls) text += "; walls at their effective positions (Gibbs depths)";
  return text;
}

namespace {

// The twin's walls at the particle walls' effective positions (Gibbs depths).
void effective_positions(const io::Json& results, const scene::SceneParameters& scene,
                         const std::array<bool, 3>& walled, CalibratedWalls& out) {
  for (int d = 0; d < scene.dim; ++d)
    for (int side = 0; side < 2; ++side) {
      if (!walled[d]) continue;
      const double depth =
          io::number(results, {"walls", scene::wall_name(d, side), "effective_position"});
      if (!std::isfinite(depth))
        throw io::InputError("particle/summary.json: no wall effective_position (a run from "
                             "before wall_layers.csv); re-run the particle stage (--force) or "
                             "set Compare/Effective walls = false");
      out.wall[d][side].position = std::max(depth, 0.0);
    }
}

// One thermal wall: its Kapitza conductance from the particle wall's heat flux q and jump, or
// (no usable jump) the fluid's temperature beside it.
void thermal_wall(double T_wall, const WallFluidTemperature& w, double q, double q_stderr,
                  bool kapitza, bool inverse, CalibratedWall& wall) {
  const double jump = T_wall - w.value;
  if (kapitza && std::isfinite(q) && q * jump > 0) {
    // h_K = q / (T_wall - T_f), or for the inverse law q / (T_wall^2 (1/T_f - 1/T_wall))
    const double driving = inverse ? T_wall * T_wall * (1 / w.value - 1 / T_wall) : jump;
    wall.conductance = q / driving;
    // Its error from q's and T_f's, taken as independent (d driving / d T_f: -T_w^2 / T_f^2
    // or -1).
    const double driving_stderr =
        (inverse ? T_wall * T_wall / (w.value * w.value) : 1.0) * w.stderr_;
    wall.conductance_stderr =
        std::fabs(wall.conductance) * std::hypot(q_stderr / q, driving_stderr / driving);
    if (!std::isfinite(wall.conductance_stderr)) wall.conductance_stderr = 0;
  } else if (std::isfinite(w.value)) {
    wall.fluid_temperature = w.value;
  }
}

void thermal_walls(const io::Json& results, const BinnedState& final_state,
                   const std::vector<char>& interior, const scene::SceneParameters& scene,
                   const TwinFacts& twin, CalibratedWalls& out) {
  for (int d = 0; d < scene.dim; ++d) {
    const auto& b = scene.boundary[d];
    // The particle wall's heat flow spread over the twin's wall, which is shorter where the
    // walls across it moved in.
    double area_ratio = 1; // scene's wall area / twin's
    for (int e = 0; e < scene.dim; ++e)
      if (e != d)
        area_ratio *=
            scene.box[e] / (scene.box[e] - out.wall[e][0].position - out.wall[e][1].position);
    for (int side = 0; side < 2; ++side) {
      if (b.periodic || !b.thermal[side]) continue;
      CalibratedWall& wall = out.wall[d][side];
      const std::string name = scene::wall_name(d, side);
      thermal_wall(b.temperature[side],
                   wall_fluid_temperature(final_state, interior, d, side, wall.position),
                   area_ratio * io::number(results, {"walls", name, "heat_flux_in"}),
                   area_ratio * particle::wall_heat_flux_stderr(results, name), out.kapitza,
                   twin.kapitza_inverse, wall);
    }
  }
}

// Navier slip from the particle wall's friction per area zeta, acting at its mean depth
// h_f: eta u'(plane) = zeta u(h_f), u(h_f) ~ u(plane) + u' (h_f - plane), so
// b = eta / zeta - (h_f - plane) (eta of the nominal twin, at its reference temperature).
void slip_lengths(const io::Json& results, const scene::SceneParameters& scene,
                  const std::array<bool, 3>& walled, const TwinFacts& twin, CalibratedWalls& out) {
  for (int d = 0; d < scene.dim; ++d)
    for (int side = 0; side < 2; ++side) {
      if (!walled[d] || !scene.boundary[d].no_slip) continue;
      const std::string name = scene::wall_name(d, side);
      const double zeta = io::number(results, {"walls", name, "friction_per_area"});
      const double depth = io::number(results, {"walls", name, "friction_depth"});
      if (!(zeta > 0) || !std::isfinite(twin.viscosity))
        throw io::InputError("particle/summary.json: no wall friction_per_area (a run from "
                             "before it); re-run the particle stage (--force) or set "
                             "Compare/Wall slip = false");
      out.wall[d][side].slip_length =
          std::max(twin.viscosity / zeta - (depth - out.wall[d][side].position), 1e-3);
    }
}

} // namespace

CalibratedWalls calibrate_walls(const io::Json& results, const BinnedState& final_state,
                                const scene::SceneParameters& scene,
                                const CompareParameters& compare, const TwinFacts& twin) {
  CalibratedWalls out;
  for (auto& direction : out.wall)
    for (auto& w : direction) w.fluid_temperature = std::nan("");
  std::array<bool, 3> walled{{false, false, false}};
  for (int d = 0; d < scene.dim; ++d) walled[d] = !scene.boundary[d].periodic;
  const auto interior = interior_bins(final_state.grid, walled, compare.wall_layer);
  out.kapitza = compare.calibration == "kapitza" && twin.robin_walls;
  if (compare.calibration == "kapitza" && !out.kapitza)
    out.notes.push_back("Kapitza walls need the Boussinesq or compressible twin; this one is "
                        "calibrated by its walls' temperatures");
  out.effective_positions = compare.effective_walls;
  if (compare.effective_walls) effective_positions(results, scene, walled, out);
  thermal_walls(results, final_state, interior, scene, twin, out);
  out.slip = compare.wall_slip && twin.robin_walls;
  if (out.slip) slip_lengths(results, scene, walled, twin, out);
  return out;
}

} // namespace twinflow::compare
