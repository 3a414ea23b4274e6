#pragma once
// The differentially heated square cavity of Le Quere et al. (2005), ESAIM: M2AN 39(3) 609-616,
// for the low-Mach model: perfect gas, hot wall x = 0 at T0 (1 + epsilon), cold wall x = 1 at
// T0 (1 - epsilon), adiabatic no-slip y walls, gravity -y, T0 = T_ref = 1, n = m = c_p = 1,
// kappa(T0) = 1 (chi = 1), eta(T0) = Pr; Ra = Pr g rho0^2 dT H^3 / (T0 mu0^2) (Le Quere 2005
// the benchmark's definition), i.e. g = Ra Pr T0 / (2 epsilon) here. Sutherland: S = 110.5 K / 600
// K in units of T0.

#include "cavity.hpp"

namespace twinflow::continuum::test_cases {

constexpr double kLeQuereSutherland = 110.5 / 600.0; // S / T0 (Le Quere et al. 2005)

inline ContinuumParameters low_mach_cavity(double rayleigh, double epsilon, bool sutherland,
                                           unsigned coarse_cells, int refinements,
                                           double prandtl = 0.71) {
  ContinuumParameters p = cavity(2, 1e3, coarse_cells, refinements);
  p.model = Model::LowMach;
  p.boundary[0].temperature = {{1.0 + epsilon, 1.0 - epsilon}};
  p.number_density = p.particle_mass = p.heat_capacity = 1.0;
  const double S = sutherland ? kLeQuereSutherland : 0.0;
  p.viscosity = PowerLaw{prandtl, 0.0, S};
  p.conductivity = PowerLaw{1.0, 0.0, S}; // k = mu c_p / Pr (constant Pr)
  p.thermal_expansion = 0.0;              // unused: the gas has alpha = 1/T0
  // Ra = g (1/T0) (2 epsilon T0) H^3 / (nu chi), nu = Pr, chi = 1, H = T0 = 1
  p.gravity = {{0.0, -rayleigh * prandtl / (2.0 * epsilon), 0.0}};
  return p;
}

} // namespace twinflow::continuum::test_cases
