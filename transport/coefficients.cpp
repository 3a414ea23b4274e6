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
  // The law c(n, T) = K (T/T0)^a + P (n/n0)^2 (T/T0)^b (laws.hpp) where the stage fitted one.
  const auto with_state_law = [&](Coefficient& c, const std::string& key) {
    const io::Json* law = io::find(summary, {"results", "measured", key + "_law"});
    if (!c.measured || !law) return false;
    const auto at = [&](const char* name) { return io::number(*law, {name}); };
    const double t = reference_temperature / at("T0");
    const double kinetic = at("K") * std::pow(t, at("a")), pair = at("P") * std::pow(t, at("b"));
    c.value = kinetic + pair;
    c.stderr_ = at("K_stderr") * std::pow(t, at("a"));
    c.exponent = at("a");
    c.pair_fraction = pair / c.value;
    c.pair_exponent = at("b");
    return true;
  };
  k.state_density = io::number(summary, {"results", "state_point", "density"});
  k.state_temperature = io::number(summary, {"results", "state_point", "temperature"});
  k.diffusion = measured("self_diffusion");
  if (!std::isfinite(k.diffusion))
    k.diffusion = io::number(summary, {"results", "estimated_measured_g", "self_diffusion"});
  k.diffusion_exponent = measured("self_diffusion_exponent");
  k.conductivity_pair =
      io::number(summary, {"results", "estimated_measured_g", "conductivity_pair_conduction"});
  if (!with_state_law(k.viscosity, "viscosity")) with_law(k.viscosity, "viscosity");
  if (!with_state_law(k.conductivity, "conductivity")) with_law(k.conductivity, "conductivity");
  return k;
}

} // namespace twinflow::transport
