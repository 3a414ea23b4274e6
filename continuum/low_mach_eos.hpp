#pragma once
// Equation of state of the low-Mach model: number density n(P, T) at the thermodynamic pressure P
// and temperature T, with the derivatives the exact Newton Jacobian needs. Particle units, k = 1
// (physics.md), so the mass density is m n.
//
// The hook for the particle fluid's measured p(n, T): add an EquationOfState value, and return
// here n(P, T) (the inverse of p(n, T) at fixed T, e.g. by a scalar Newton solve on a fitted or
// tabulated p) and its derivatives. Nothing else in the solver assumes the ideal gas: the
// thermodynamic pressure is found from the mass by a scalar Newton solve on int n(P, T) dV = N.

#include "continuum/parameters.hpp"

namespace twinflow::continuum {

struct DensityState {
  double n = 0;    // number density
  double n_T = 0;  // dn/dT at fixed P
  double n_TT = 0; // d2n/dT2
  double n_P = 0;  // dn/dP at fixed T
  double n_TP = 0; // d2n/dTdP
};

inline DensityState number_density(EquationOfState eos, double P, double T) {
  DensityState s;
  switch (eos) {
  case EquationOfState::IdealGas:
    // n = P / (k T), k = 1 (physics.md: p = rho k T for the ideal DPDE fluid)
    s.n = P / T;
    s.n_T = -P / (T * T);
    s.n_TT = 2 * P / (T * T * T);
    s.n_P = 1 / T;
    s.n_TP = -1 / (T * T);
    break;
  }
  return s;
}

} // namespace twinflow::continuum
