#include "transport/measurement.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <utility>

#include "transport/estimates.hpp"
#include "transport/measure.hpp"

namespace twinflow::transport {

particle::ParticleParameters bulk_fluid(const scene::SceneParameters& scene,
                                        const particle::ParticleParameters& scene_fluid,
                                        const TransportParameters& t) {
  particle::ParticleParameters p = scene_fluid;
  if (scene.thermal_wall_mean() > 0) p.temperature = scene.thermal_wall_mean();
  if (t.temperature > 0) p.temperature = t.temperature;
  // Bulk runs start in equilibrium at the state point, whatever the scene's own start (a case
  // that starts at rest, or with theta_i = T, would otherwise measure at a lower temperature:
  // T (c_v + d/2) / (c_v + 1 + d/2), 8% low at c_v = 10).
  p.initial_velocities = particle::InitialVelocities::Maxwell;
  p.initial_internal_energy = particle::InitialInternalEnergy::Equilibrium;
  p.temperature_perturbation = 0;
  p.shear_perturbation = 0;
  p.poiseuille_force = 0;
  p.gravity = {{0, 0, 0}};
  for (auto& w : p.walls) w.present = false;
  p.heat_slabs.clear();
  const double edge = std::max(3 * p.largest_cutoff(), std::pow(4000 / p.density, 1.0 / p.dim));
  p.box = {{edge, edge, edge}};
  return p;
}

TransportMeasurement measure_transport(const scene::SceneParameters& scene,
                                       const particle::ParticleParameters& scene_fluid,
                                       const particle::ParticleParameters& p,
                                       const TransportParameters& t) {
  TransportMeasurement out;
  io::Json& r = out.results;
  const double nan = std::nan("");
  const Estimates ideal = estimate(p, p.temperature, PairDistribution::ideal());
  const long steps = 2000;
  const Measured m = measure(p, steps, t.diffusion_repeats);
  const auto measured_g = PairDistribution::from_csv(m.rdf_csv);
  const Estimates with_g = estimate(p, p.temperature, measured_g);
  particle::Estimate kappa{nan, nan}, eta{nan, nan};
  RelaxationCoefficients flow;
  // With a temperature spread s, also at T (1 -+ s): kappa(T) and eta(T) as power laws.
  std::vector<double> temperatures{p.temperature};
  const double spread = t.temperature_spread;
  if (spread > 0)
    temperatures = {p.temperature * (1 - spread), p.temperature, p.temperature * (1 + spread)};
  std::vector<RelaxationCoefficients> at_temperature;
  // The relaxation runs' own, smaller box: they last a few relaxation times of the box, ~ L^2.
  const double flow_edge =
      std::max(3 * p.largest_cutoff(), std::pow(t.flow_particles / p.density, 1.0 / p.dim));
  // The modes' wavelength is the doubled box edge; hydrodynamics needs it long against the
  // interaction range (k rc << 1), else the coefficients are those of a finite wavenumber.
  const double k_rc = 2 * M_PI / (2 * flow_edge) * p.largest_cutoff();
  if (t.measure_flows) {
    // c_p per particle: the ideal fluid's for the ideal gas (estimate); with conservative forces
    // the same is an approximation (the measured c_p - c_v is reported beside it).
    particle::ParticleParameters flows = p;
    flows.box = {{flow_edge, flow_edge, flow_edge}};
    const int repeats = t.flow_repeats;
    const int total = repeats * static_cast<int>(temperatures.size());
    if (k_rc > 0.3)
      std::cout << "transport: the relaxation modes have k rc = " << k_rc << " (wavelength "
                << 2 * flow_edge / p.largest_cutoff()
                << " cutoffs): coefficients at that finite wavenumber; more Transport/Flow "
                   "particles lower it (k rc ~ N^(-1/d))\n";
    const auto flow_start = std::chrono::steady_clock::now();
    int done_before = 0;
    for (std::size_t i = 0; i < temperatures.size(); ++i) {
      const double t = temperatures[i];
      flows.temperature = t;
      flows.seed = p.seed + 104729 * i; // independent runs at each temperature
      const Estimates guess = estimate(flows, t, measured_g);
      at_temperature.push_back(measure_relaxation(
          flows, guess, guess.heat_capacity_p, repeats,
          [&](int done, const RelaxationCoefficients& so_far) {
            const double spent =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - flow_start)
                    .count();
            const int all = done_before + done;
            const auto& run_k = so_far.conductivity.repeats.back();
            const auto& run_e = so_far.viscosity.repeats.back();
            std::printf("transport: relaxation at T = %.4g, run %d/%d (N = %ld, %ld steps): kappa "
                        "%.4g +- %.2g, eta %.4g +- %.2g; %.0f s, ETA %.0f s\n",
                        t, done, repeats, so_far.particles, so_far.steps, run_k.mean, run_k.stderr_,
                        run_e.mean, run_e.stderr_, spent, spent / all * (total - all));
            std::fflush(stdout);
          }));
      done_before += repeats;
    }
    flow = at_temperature[temperatures.size() / 2];
    kappa = flow.conductivity.value;
    eta = flow.viscosity.value;
  }
  WallKappa by_walls;
  if (t.kappa_from_walls) {
    by_walls = kappa_from_walls(scene, scene_fluid, p.temperature, t.wall_steps);
    kappa = by_walls.kappa;
  }
  // The relaxation runs' own temperatures (the state they measured), where known.
  std::vector<double> measured_at = temperatures;
  for (std::size_t i = 0; i < at_temperature.size(); ++i)
    if (std::isfinite(at_temperature[i].temperature.value.mean))
      measured_at[i] = at_temperature[i].temperature.value.mean;
  const double state_temperature =
      at_temperature.empty() ? p.temperature : measured_at[temperatures.size() / 2];
  PowerLawFit kappa_law, eta_law;
  if (at_temperature.size() > 1) {
    std::vector<particle::Estimate> k, e;
    for (const auto& a : at_temperature)
      k.push_back(a.conductivity.value), e.push_back(a.viscosity.value);
    kappa_law = fit_power_law(measured_at, k, state_temperature);
    eta_law = fit_power_law(measured_at, e, state_temperature);
  }

  std::ostringstream table;
  char line[256];
  std::snprintf(line, sizeof line,
                "# state point: rho = %g, T = %g (%dD periodic box, N = %ld); kappa and eta "
                "measured at T = %.4g (the relaxation runs' own)\n",
                p.density, p.temperature, p.dim, p.particle_count(), state_temperature);
  table << line
        << "coefficient,estimate_g1,estimate_measured_g,measured,measured_stderr,"
           "measured/estimate\n";
  auto row = [&](const char* name, double e1, double eg, double meas, double se) {
    std::snprintf(line, sizeof line, "%s,%.6g,%.6g,%.6g,%.3g,%.4f\n", name, e1, eg, meas, se,
                  std::isnan(meas) ? NAN : meas / eg);
    table << line;
  };
  row("self_diffusion_D", ideal.diffusion, with_g.diffusion, m.diffusion.mean, m.diffusion.stderr_);
  row("viscosity_eta", ideal.viscosity, with_g.viscosity, eta.mean, eta.stderr_);
  row("conductivity_kappa", ideal.conductivity, with_g.conductivity, kappa.mean, kappa.stderr_);
  if (at_temperature.size() > 1) {
    for (std::size_t i = 0; i < temperatures.size(); ++i) {
      char at[32];
      std::snprintf(at, sizeof at, "_at_T_%.4g", measured_at[i]);
      row(("viscosity_eta" + std::string(at)).c_str(), nan, nan,
          at_temperature[i].viscosity.value.mean, at_temperature[i].viscosity.value.stderr_);
      row(("conductivity_kappa" + std::string(at)).c_str(), nan, nan,
          at_temperature[i].conductivity.value.mean, at_temperature[i].conductivity.value.stderr_);
    }
    row("viscosity_exponent_n_in_T^n", nan, nan, eta_law.exponent, eta_law.exponent_stderr);
    row("conductivity_exponent_n_in_T^n", nan, nan, kappa_law.exponent, kappa_law.exponent_stderr);
  }
  row("conductivity_kappa_002_eq22", ideal.conductivity_002_eq22, with_g.conductivity_002_eq22, nan,
      nan);
  row("thermal_expansion_alpha", ideal.expansion, with_g.expansion, m.expansion.mean,
      m.expansion.stderr_);
  row("pressure_ideal_gas", p.density * p.temperature, p.density * p.temperature, m.pressure.mean,
      m.pressure.stderr_);
  // p = n T + n^2 (b0 + b1 T + b2 (n - n_ref)): the compressible twin's equation of state
  row("excess_pressure_b0", nan, nan, m.excess_pressure.b0, m.excess_pressure.b0_stderr);
  row("excess_pressure_b1", nan, nan, m.excess_pressure.b1, m.excess_pressure.b1_stderr);
  row("excess_pressure_b2", nan, nan, m.excess_pressure.b2, m.excess_pressure.b2_stderr);
  row("heat_capacity_cv_per_particle", ideal.heat_capacity_v, with_g.heat_capacity_v, nan, nan);
  row("heat_capacity_cp_per_particle", ideal.heat_capacity_p, with_g.heat_capacity_p, nan, nan);
  row("heat_capacity_cp_minus_cv_per_particle", ideal.heat_capacity_p - ideal.heat_capacity_v,
      with_g.heat_capacity_p - with_g.heat_capacity_v, m.cp_minus_cv.mean, m.cp_minus_cv.stderr_);
  row("prandtl", ideal.prandtl, with_g.prandtl, nan, nan);
  row("schmidt", ideal.schmidt, with_g.schmidt, nan, nan);
  r["state_point"]["density"] = p.density;
  r["state_point"]["temperature"] = p.temperature;
  // The temperature the measured kappa and eta belong to (the relaxation runs' own).
  r["state_point"]["measured_temperature"] = state_temperature;
  r["estimated_g1"] = ideal.json();
  r["estimated_measured_g"] = with_g.json();
  r["measured"] = m.json();
  // The twins' equation of state (transport/coefficients.cpp): the ideal fluid's without a
  // conservative force (exact; the fit's b0, b1, b2 are then noise about 0), else the fit.
  io::Json eos = io::Json::object();
  const bool ideal_fluid = p.conservative == particle::ConservativeForce::None;
  eos["form"] = "p = n k T + n^2 (b0 + b1 k T + b2 (n - n_ref))";
  eos["n_ref"] = p.density;
  eos["source"] = ideal_fluid ? "ideal DPDE fluid (no conservative force)"
                              : "fit to the bulk runs (measured/excess_pressure)";
  const ExcessPressureFit& fit = m.excess_pressure;
  for (const auto& [key, value] : {std::pair{"b0", fit.b0},
                                   {"b0_stderr", fit.b0_stderr},
                                   {"b1", fit.b1},
                                   {"b1_stderr", fit.b1_stderr},
                                   {"b2", fit.b2},
                                   {"b2_stderr", fit.b2_stderr}})
    eos[key] = ideal_fluid ? 0.0 : value;
  r["equation_of_state"] = eos;
  // The continuum twin reads "conductivity" and "viscosity" (transport/coefficients.cpp).
  if (t.kappa_from_walls || t.measure_flows) {
    r["measured"]["conductivity"] = kappa.mean;
    r["measured"]["conductivity_stderr"] = kappa.stderr_;
  }
  if (t.kappa_from_walls) r["measured"]["walls"] = by_walls.json;
  if (t.measure_flows) {
    if (t.kappa_from_walls) {
      r["measured"]["conductivity_relaxation"] = flow.conductivity.value.mean;
      r["measured"]["conductivity_relaxation_stderr"] = flow.conductivity.value.stderr_;
    }
    r["measured"]["viscosity"] = eta.mean;
    r["measured"]["viscosity_stderr"] = eta.stderr_;
    io::Json method = io::Json::object();
    method["method"] = "heat and transverse-momentum modes decaying in a periodic box (seed 004)";
    method["particles"] = flow.particles;
    method["wavenumber_times_cutoff"] = k_rc;
    method["steps"] = flow.steps;
    method["conductivity"] = flow.conductivity.json();
    method["viscosity"] = flow.viscosity.json();
    r["measured"]["relaxation"] = method;
    if (at_temperature.size() > 1) {
      // The continuum twin reads the exponents (transport/coefficients.cpp).
      io::Json law = io::Json::object();
      law["reference_temperature"] = state_temperature;
      law["temperatures"] = io::Json::array();
      law["conductivity"] = io::Json::array();
      law["viscosity"] = io::Json::array();
      for (std::size_t i = 0; i < temperatures.size(); ++i) {
        law["temperatures"].push_back(measured_at[i]);
        law["conductivity"].push_back(at_temperature[i].conductivity.json());
        law["viscosity"].push_back(at_temperature[i].viscosity.json());
      }
      law["conductivity_chi2_per_dof"] = kappa_law.chi2_per_dof;
      law["viscosity_chi2_per_dof"] = eta_law.chi2_per_dof;
      r["measured"]["temperature_dependence"] = law;
      r["measured"]["conductivity_exponent"] = kappa_law.exponent;
      r["measured"]["conductivity_exponent_stderr"] = kappa_law.exponent_stderr;
      r["measured"]["viscosity_exponent"] = eta_law.exponent;
      r["measured"]["viscosity_exponent_stderr"] = eta_law.exponent_stderr;
    }
    std::ostringstream note; // the ideal fluid's c_p = c_v + k + (d/2 + 1) k (000:(3.21))
    note << "kappa = rho c_p chi with the ideal fluid's c_p = " << with_g.heat_capacity_p
         << " k per particle; the relaxation box holds ~" << t.flow_particles
         << " particles (x2): in 2D its coefficients depend on the box (long-time tails). Errors: "
            "the larger of the repeats' spread and the fits' own errors, over sqrt(repeats)";
    r["measured"]["conductivity_note"] = note.str();
  }
  out.coefficients_csv = table.str();
  out.rdf_csv = m.rdf_csv;
  return out;
}

} // namespace twinflow::transport
