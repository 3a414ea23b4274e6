#include "transport/coefficients.hpp"

#include <cmath>

#include "io/files.hpp"

namespace twinflow::transport {

Coefficients read_coefficients(const io::Json& summary, const std::string& source,
                               double reference_temperature) {
  const double nan = std::nan("");
  if (!io::find(summary, {"results", "estimated_measured_g"}))
    throw io::InputError("transport summary: no results/estimated_measured_g");
  const auto measured = [&](const std::string& key) {
    return io::number(summary, {"results", "measured", key});
  };
  const auto pick = [&](const char* estimate_key, const char* measured_key) {
    Coefficient c{io::number(summary, {"results", "estimated_measured_g", estimate_key}), nan, nan,
                  false};
    const double m = measured_key ? measured(measured_key) : nan;
    if (source == "measured" && std::isfinite(m)) c.value = m, c.measured = true;
    return c;
  };
  Coefficients k;
  k.measured_temperature = io::number(summary, {"results", "state_point", "measured_temperature"});
  k.viscosity = pick("viscosity", "viscosity");
  k.conductivity = pick("conductivity", "conductivity");
  k.heat_capacity_p = pick("heat_capacity_p_per_particle", nullptr);
  k.viscosity_dissipative =
      io::number(summary, {"results", "estimated_measured_g", "viscosity_dissipative"});
  k.thermal_expansion = pick("thermal_expansion", "thermal_expansion");
  // Measured kappa and eta carry errors, and with a temperature spread a power law.
  const auto with_law = [&](Coefficient& c, const std::string& key) {
    if (!c.measured) return;
    c.stderr_ = measured(key + "_stderr");
    const double n = measured(key + "_exponent");
    if (!std::isfinite(n) || !std::isfinite(k.measured_temperature)) return;
    const double log_ratio = std::log(reference_temperature / k.measured_temperature);
    const double scale = std::exp(n * log_ratio);
    const double n_stderr = measured(key + "_exponent_stderr");
    c.stderr_ = scale * std::hypot(c.stderr_, c.value * log_ratio * n_stderr);
    c.exponent = n;
    c.value *= scale;
  };
  if (const io::Json* eos = io::find(summary, {"results", "equation_of_state"})) {
    const auto at = [&](const char* key) { return io::number(*eos, {key}); };
    auto& e = k.excess_pressure;
    e.b0 = at("b0"), e.b1 = at("b1"), e.b2 = at("b2"), e.n_ref = at("n_ref");
    e.b0_stderr = at("b0_stderr"), e.b1_stderr = at("b1_stderr"), e.b2_stderr = at("b2_stderr");
    e.fitted = e.b0 != 0 || e.b1 != 0 || e.b2 != 0;
    e.found = true;
  }
  with_law(k.viscosity, "viscosity");
  with_law(k.conductivity, "conductivity");
  return k;
}

} // namespace twinflow::transport
