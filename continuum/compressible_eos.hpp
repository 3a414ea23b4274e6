#pragma once
// Equation of state of the compressible model (continuum/compressible.hpp): the pressure p(n, T)
// with the derivatives the exact Newton Jacobian needs, and the heat capacity per particle at
// constant volume c_V = (de/dT)_n. Particle units, k = 1 (physics.md).
//
// Ideal DPDE fluid (no conservative force): p = n k T (000:(3.20)) and the energy per particle
// e = (d/2) k T + (c_v + k) T (000:(3.21)), so c_V = c_p - k is constant and (de/dn)_T = 0.
// The hook for the particle fluid's measured p(n, T) with a conservative force (the transport
// stage's bulk runs at a few densities and temperatures): add an EquationOfState value and return
// its fitted p and derivatives here, and its c_V(n, T) (then with derivatives, which the model's
// Jacobian would need: today it takes c_V constant). Not done yet.

#include "continuum/parameters.hpp"

namespace twinflow::continuum {

struct PressureState {
  double p = 0;            // pressure
  double p_n = 0, p_T = 0; // dp/dn at fixed T, dp/dT at fixed n
  double p_nn = 0, p_nT = 0, p_TT = 0;
};

struct PressureWork {
  double value = 0, d_n = 0, d_T = 0; // T p_T and its derivatives in n and T
};

inline PressureState pressure(EquationOfState eos, double n, double T) {
  PressureState s;
  switch (eos) {
  case EquationOfState::IdealGas:
    // p = n k T, k = 1 (000:(3.20))
    s.p = n * T;
    s.p_n = T;
    s.p_T = n;
    s.p_nT = 1;
    break;
  }
  return s;
}

// The pressure work of the internal-energy equation, T (dp/dT)_n div u (Landau & Lifshitz,
// Fluid Mechanics, sec. 49, with the Maxwell relation (ds/dv)_T = (dp/dT)_v), and its derivatives
// in n and T (ideal gas: p itself).
inline PressureWork pressure_work(const PressureState& s, double T) {
  return {T * s.p_T, T * s.p_nT, s.p_T + T * s.p_TT};
}

// c_V per particle, (de/dT)_n: the ideal DPDE fluid's c_v + k + (d/2) k (000:(3.21)), which is
// c_p - k for the ideal gas (physics.md: c_p adds k). `heat_capacity_p` is the case's c_p.
inline double heat_capacity_v(EquationOfState eos, double heat_capacity_p) {
  switch (eos) {
  case EquationOfState::IdealGas:
    return heat_capacity_p - 1.0; // c_V = c_p - k, k = 1 (physics.md)
  }
  return heat_capacity_p;
}

} // namespace twinflow::continuum
