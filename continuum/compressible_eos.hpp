#pragma once
// Equation of state of the compressible model (continuum/compressible.hpp): the pressure p(n, T)
// with the derivatives the exact Newton Jacobian needs, and the heat capacity per particle at
// constant volume c_V = (de/dT)_n. Particle units, k = 1 (docs/theory.md).
//
// p = n k T + n^2 B, B = b0 + b1 k T + b2 (n - n_ref): the ideal DPDE fluid at B = 0
// (000:(3.20)); with a conservative force, the transport stage's fit to its bulk runs
// (transport/measure.hpp). Thermodynamic consistency fixes the energy: (de/dn)_T =
// (p - T p_T) / n^2 = b0 + b2 (n - n_ref) (the Maxwell relation (dE/dV)_T = T p_T - p; Landau &
// Lifshitz, Statistical Physics, sec. 16) does not depend on T, so c_V = (de/dT)_n is the ideal
// fluid's. The energy equation n c_V DT/Dt = -T p_T div u + ... (compressible.hpp) needs
// nothing more.

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

inline PressureState pressure(const EquationOfState& eos, double n, double T) {
  const double B = eos.b0 + eos.b1 * T + eos.b2 * (n - eos.n_ref); // excess pressure / n^2
  PressureState s;
  s.p = n * T + n * n * B; // 000:(3.20) plus the fitted excess n^2 B
  s.p_n = T + 2 * n * B + n * n * eos.b2;
  s.p_T = n + n * n * eos.b1;
  s.p_nn = 2 * B + 4 * n * eos.b2;
  s.p_nT = 1 + 2 * n * eos.b1;
  s.p_TT = 0;
  return s;
}

// The pressure work of the internal-energy equation, T (dp/dT)_n div u (Landau & Lifshitz,
// Fluid Mechanics, sec. 49, with the Maxwell relation (ds/dv)_T = (dp/dT)_v), and its derivatives
// in n and T.
inline PressureWork pressure_work(const PressureState& s, double T) {
  return {T * s.p_T, T * s.p_nT, s.p_T + T * s.p_TT};
}

// c_V per particle, (de/dT)_n: the ideal DPDE fluid's c_v + k + (d/2) k (000:(3.21)), which is
// c_p - k of the ideal fluid (docs/theory.md: c_p adds k); the excess pressure adds none (above).
// `ideal_heat_capacity_p` is the case's c_p, the ideal fluid's.
inline double heat_capacity_v(double ideal_heat_capacity_p) {
  return ideal_heat_capacity_p - 1.0; // c_V = c_p - k, k = 1 (docs/theory.md)
}

} // namespace twinflow::continuum
