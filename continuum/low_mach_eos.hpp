#pragma once
// Equation of state of the low-Mach model: number density n(P, T) at the thermodynamic pressure P
// and temperature T, with the derivatives the exact Newton Jacobian needs. Particle units, k = 1
// (docs/theory.md), so the mass density is m n.
//
// The ideal fluid only (continuum::check refuses an excess pressure here): its energy equation
// takes c_p constant and the ideal gas's dP/dt work; a non-ideal p(n, T) needs c_p(n, T) and
// alpha_p T dP/dt there, and here n(P, T) by solving p(n, T) = P. The compressible
// model takes the fitted p(n, T) of a fluid with a conservative force.

#include "continuum/parameters.hpp"

namespace twinflow::continuum {

struct DensityState {
  double n = 0;    // number density
  double n_T = 0;  // dn/dT at fixed P
  double n_TT = 0; // d2n/dT2
  double n_P = 0;  // dn/dP at fixed T
  double n_TP = 0; // d2n/dTdP
};

inline DensityState number_density(double P, double T) {
  DensityState s;
  // n = P / (k T), k = 1 (docs/theory.md: p = rho k T for the ideal DPDE fluid)
  s.n = P / T;
  s.n_T = -P / (T * T);
  s.n_TT = 2 * P / (T * T * T);
  s.n_P = 1 / T;
  s.n_TP = -1 / (T * T);
  return s;
}

} // namespace twinflow::continuum
