#pragma once
// The scene both twins share: the box, its boundaries, gravity, heat slabs and the bins on
// which the fields are compared. The particle and continuum parameters are derived from it.

#include <array>
#include <string>
#include <vector>

namespace twinflow::scene {

// Boundaries of one box direction.
struct DirectionBoundary {
  bool periodic = true;
  std::array<bool, 2> thermal{{true, true}}; // lower, upper: thermal (true) or adiabatic
  std::array<double, 2> temperature{{1.0, 1.0}};
  bool no_slip = false;
};

// A slab x_d in [lower, upper] into which `power` (energy per time; < 0: out of) is put.
struct HeatSlab {
  int direction;
  double lower, upper, power;
};

struct SceneParameters {
  int dim = 3;
  std::array<double, 3> box{{20, 10, 10}};
  double density = 3.0;
  double temperature = 1.0;
  double temperature_perturbation = 0; // relative amplitude of sin(2 pi x / Lx) at the start
  double shear_perturbation = 0;       // v_y amplitude of sin(2 pi x / Lx), in sqrt(k T / m)
  double poiseuille_force = 0;         // reverse Poiseuille: +F x-hat for y < Ly/2, -F above
  std::array<double, 3> gravity{{0, 0, 0}};
  std::array<DirectionBoundary, 3> boundary;
  std::vector<HeatSlab> heat_slabs;   // hot then cold
  std::array<int, 3> bins{{1, 1, 1}}; // field bins shared by both twins

  bool has_walls() const;
  // The walled direction whose two thermal walls differ in temperature; -1: none.
  int heated_direction() const;
  // (T_max - T_min) / (T_max + T_min) over the thermal walls (Le Quere et al. 2005); 0: none.
  double thermal_wall_epsilon() const;
  // The mean temperature of the thermal walls; 0 without any.
  double thermal_wall_mean() const;
  // The density at temperature T on the isobar of the box at rest with a linear temperature
  // between the heated direction's walls (ideal gas, int n dV = N): p = n0 (T_h - T_c) /
  // ln(T_h / T_c), n = p / T. The scene's density without a heated direction.
  double density_on_isobar(double T) const;
  // Stratification g H / c^2 (docs/theory.md, "What a convection scene costs"): g the largest
  // gravity component, H the box along it, c^2 = k T / m the ideal DPDE fluid's isothermal sound
  // speed at the thermal walls' mean temperature (else the scene's); 0 without gravity.
  double stratification(double particle_mass) const;
};

// A wall's name in the outputs: "x_lower", "y_upper", ...
std::string wall_name(int direction, int side);

} // namespace twinflow::scene
