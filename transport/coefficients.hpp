#pragma once
// The one reader of the transport stage's results (transport/summary.json): the coefficient a
// consumer takes is the measured one where the case asks for measured coefficients and the
// stage measured it, else the estimate with the measured g(r). Used by the continuum twin and
// by `sweep --rayleigh`, so that both take the same numbers.

#include <cmath>
#include <string>

#include "io/json.hpp"

namespace twinflow::transport {

struct Coefficient {
  double value = 0; // at the requested temperature
  double stderr_;   // NaN for an estimate
  double exponent;  // of a measured power law value (T / T_ref)^n; NaN: none
  bool measured = false;
  // A measured law c(n, T) (transport/laws.hpp) at the requested temperature T_ref: the pair
  // part's fraction there and its power of T (the rest goes as T^exponent and not with n).
  double pair_fraction = 0, pair_exponent = 0;
  double exponent_stderr = std::nan(""); // the fit's error of `exponent`
};

// p = n k T + n^2 (b0 + b1 k T + b2 (n - n_ref)): the ideal fluid (all 0) or the fit of a fluid
// with a conservative force (transport/measure.hpp).
struct ExcessPressure {
  double b0 = 0, b1 = 0, b2 = 0, n_ref = 1;
  double b0_stderr = 0, b1_stderr = 0, b2_stderr = 0;
  bool fitted = false; // else the ideal fluid's
  bool found = false;  // false: a summary of an older method, which has none
};

struct Coefficients {
  Coefficient viscosity, conductivity, heat_capacity_p, thermal_expansion;
  ExcessPressure excess_pressure; // whatever the source: the pressure is always measured
  // The dissipative part of eta's estimate (with the measured g(r)): the compressible twin's bulk
  // viscosity (1 + 2/d) eta_D (Marsh, Backx & Ernst 1997). NaN: not in the summary.
  double viscosity_dissipative = 0;
  double measured_temperature; // where the measured kappa and eta belong (NaN: not measured)
  // D at the state point (measured, else the estimate) and its power of T (NaN: not measured),
  // at the state point's density and temperature: what the wall layer's theory takes.
  double diffusion = 0, diffusion_exponent = 0, state_density = 0, state_temperature = 0;
  // The pair part of kappa at the state point (theory with the measured g) and its power of T.
  double conductivity_pair = 0;
};

// `source`: "measured" or "estimated" (Transport/Source). A measured law c(n, T)
// (conductivity_law, viscosity_law) is evaluated at the reference temperature and the state
// point's density, its error K's. Else a measured power law (Transport/Temperature spread) is
// rescaled from the measured temperature to `reference_temperature`, its
// error with the exponent's: sigma^2 = s^2 [sigma_c^2 + c^2 ln^2(T_ref / T_m) sigma_n^2].
// Throws io::InputError when the summary lacks the estimates.
Coefficients read_coefficients(const io::Json& summary, const std::string& source,
                               double reference_temperature);

} // namespace twinflow::transport
