#pragma once
// The one reader of the transport stage's results (transport/summary.json): the coefficient a
// consumer takes is the measured one where the case asks for measured coefficients and the
// stage measured it, else the estimate with the measured g(r). Used by the continuum twin and
// by `sweep --rayleigh`, so that both take the same numbers.

#include <string>

#include "io/json.hpp"

namespace twinflow::transport {

struct Coefficient {
  double value = 0; // at the requested temperature
  double stderr_;   // NaN for an estimate
  double exponent;  // of a measured power law value (T / T_ref)^n; NaN: none
  bool measured = false;
};

struct Coefficients {
  Coefficient viscosity, conductivity, heat_capacity_p, thermal_expansion;
  double measured_temperature; // where the measured kappa and eta belong (NaN: not measured)
};

// `source`: "measured" or "estimated" (Transport/Source). A measured power law (Transport/
// Temperature spread) is rescaled from the measured temperature to `reference_temperature`, its
// error with the exponent's: sigma^2 = s^2 [sigma_c^2 + c^2 ln^2(T_ref / T_m) sigma_n^2].
// Throws io::InputError when the summary lacks the estimates.
Coefficients read_coefficients(const io::Json& summary, const std::string& source,
                               double reference_temperature);

} // namespace twinflow::transport
