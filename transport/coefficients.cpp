#include "transport/coefficients.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "io/files.hpp"
#include "transport/laws.hpp"

namespace twinflow::transport {

namespace {

double measured(const io::Json& summary, const std::string& key) {
  return io::number(summary, {"results", "measured", key});
}

// A measured kappa or eta with its error, moved to the reference temperature along the power law
// fitted over the measurements' temperature spread (where there was one).
void with_power_law(const io::Json& summary, const std::string& key, double measured_temperature,
                    double reference_temperature, Coefficient& c) {
  if (!c.measured) return;
  c.stderr_ = measured(summary, key + "_stderr");
  const double n = measured(summary, key + "_exponent");
  if (!std::isfinite(n) || !std::isfinite(measured_temperature)) return;
  const double log_ratio = std::log(reference_temperature / measured_temperature);
  const double scale = std::exp(n * log_ratio);
  const double n_stderr = measured(summary, key + "_exponent_stderr");
  c.stderr_ = scale * std::hypot(c.stderr_, c.value * log_ratio * n_stderr);
  c.exponent = n;
  c.exponent_stderr = n_stderr;
  c.value *= scale;
}

// The law c(n, T) = K (T/T0)^a + P (n/n0)^2 (T/T0)^b (laws.hpp) where the stage fitted one.
bool with_state_law(const io::Json& summary, const std::string& key, double reference_temperature,
                    Coefficient& c) {
  const io::Json* law = io::find(summary, {"results", "measured", key + "_law"});
  if (!c.measured || !law) return false;
  const CoefficientLaw l = CoefficientLaw::from_json(*law);
  c.value = l.at(l.n0, reference_temperature);
  c.stderr_ = l.stderr_at(reference_temperature);
  c.exponent = l.a;
  c.exponent_stderr = l.a_stderr;
  c.pair_fraction = l.pair_fraction(reference_temperature);
  c.pair_exponent = l.b;
  return true;
}

ExcessPressure excess_pressure(const io::Json& eos) {
  const auto at = [&](const char* key) { return io::number(eos, {key}); };
  ExcessPressure e;
  e.b0 = at("b0"), e.b1 = at("b1"), e.b2 = at("b2"), e.n_ref = at("n_ref");
  e.b0_stderr = at("b0_stderr"), e.b1_stderr = at("b1_stderr"), e.b2_stderr = at("b2_stderr");
  e.fitted = e.b0 != 0 || e.b1 != 0 || e.b2 != 0;
  e.found = true;
  return e;
}

} // namespace

Coefficients read_coefficients(const io::Json& summary, const std::string& source,
                               double reference_temperature) {
  const double nan = std::nan("");
  if (!io::find(summary, {"results", "estimated_measured_g"}))
    throw io::InputError("transport summary: no results/estimated_measured_g");
  const auto estimate = [&](const char* key) {
    return io::number(summary, {"results", "estimated_measured_g", key});
  };
  // The estimate, or the measurement where the case asks for it and the stage made one.
  const auto pick = [&](const char* estimate_key, const char* measured_key) {
    Coefficient c{estimate(estimate_key), nan, nan, false};
    const double m = measured_key ? measured(summary, measured_key) : nan;
    if (source == "measured" && std::isfinite(m)) c.value = m, c.measured = true;
    return c;
  };
  Coefficients k;
  k.measured_temperature = io::number(summary, {"results", "state_point", "measured_temperature"});
  k.viscosity = pick("viscosity", "viscosity");
  k.conductivity = pick("conductivity", "conductivity");
  k.heat_capacity_p = pick("heat_capacity_p_per_particle", nullptr);
  k.viscosity_dissipative = estimate("viscosity_dissipative");
  k.thermal_expansion = pick("thermal_expansion", "thermal_expansion");
  if (const io::Json* eos = io::find(summary, {"results", "equation_of_state"}))
    k.excess_pressure = excess_pressure(*eos);
  k.state_density = io::number(summary, {"results", "state_point", "density"});
  k.state_temperature = io::number(summary, {"results", "state_point", "temperature"});
  k.diffusion = measured(summary, "self_diffusion");
  if (!std::isfinite(k.diffusion)) k.diffusion = estimate("self_diffusion");
  k.diffusion_exponent = measured(summary, "self_diffusion_exponent");
  k.conductivity_pair = estimate("conductivity_pair_conduction");
  for (auto [c, key] :
       {std::pair{&k.viscosity, "viscosity"}, std::pair{&k.conductivity, "conductivity"}})
    if (!with_state_law(summary, key, reference_temperature, *c))
      with_power_law(summary, key, k.measured_temperature, reference_temperature, *c);
  return k;
}

} // namespace twinflow::transport
