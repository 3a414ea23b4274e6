#include "transport/measurement.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <tuple>
#include <utility>

#include "transport/estimates.hpp"
#include "transport/jobs.hpp"
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

std::vector<std::pair<double, double>> isobar_ends(const scene::SceneParameters& scene,
                                                   const TransportParameters& t) {
  std::vector<std::pair<double, double>> ends;
  const int heated = scene.heated_direction();
  if (t.measure_flows && t.viscosity_along_isobar && heated >= 0)
    for (const double T : scene.boundary[heated].temperature)
      ends.emplace_back(scene.density_on_isobar(T), T);
  return ends;
}

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// D's power of T is measured at T (1 -+ this) (eta's kinetic part rides on it).
constexpr double kDiffusionSpread = 0.25;

// What the stage measured, step by step (measure_transport below).
struct Plan {
  const scene::SceneParameters& scene;
  const particle::ParticleParameters& scene_fluid;
  const particle::ParticleParameters& p; // the bulk fluid at the state point
  const TransportParameters& t;
  bool slabs = false; // kappa (and its law) from periodic heat slabs at the scene's scale
  std::vector<double> temperatures;
  // eta's law is also measured at the heated walls' (n, T) on the isobar (laws.hpp)
  std::vector<std::pair<double, double>> isobar_ends;
  double flow_edge = 0, k_rc = 0;
};

struct Results {
  Estimates ideal, with_g;
  Measured bulk;
  std::vector<RelaxationCoefficients> at_temperature, at_isobar_ends;
  RelaxationCoefficients flow;
  SlabKappa slab;
  WallKappa walls;
  particle::Estimate kappa{NAN, NAN}, eta{NAN, NAN};
  CoefficientLaw kappa_law, eta_law;
  bool has_laws = false;
  std::vector<double> measured_at;
  double state_temperature = 0;
  PowerLawFit kappa_power, eta_power;
};

Plan make_plan(const scene::SceneParameters& scene, const particle::ParticleParameters& scene_fluid,
               const particle::ParticleParameters& p, const TransportParameters& t) {
  Plan plan{scene, scene_fluid, p, t, false, {}, {}, 0, 0};
  plan.slabs = t.measure_flows && t.kappa_from_slabs && scene.heated_direction() >= 0;
  plan.isobar_ends = isobar_ends(scene, t);
  plan.temperatures = {p.temperature};
  const double s = t.temperature_spread;
  if (s > 0) plan.temperatures = {p.temperature * (1 - s), p.temperature, p.temperature * (1 + s)};
  // The relaxation runs' own, smaller box: they last a few relaxation times of the box, ~ L^2.
  plan.flow_edge =
      std::max(3 * p.largest_cutoff(), std::pow(t.flow_particles / p.density, 1.0 / p.dim));
  // The modes' wavelength is the doubled box edge; hydrodynamics needs it long against the
  // interaction range (k rc << 1), else the coefficients are those of a finite wavenumber.
  plan.k_rc = 2 * M_PI / (2 * plan.flow_edge) * p.largest_cutoff();
  return plan;
}

// Step 1: the bulk runs (equation of state, D and its power of T, g(r)) and the estimates.
void measure_bulk(const Plan& plan, Results& r) {
  const particle::ParticleParameters& p = plan.p;
  r.ideal = estimate(p, p.temperature, PairDistribution::ideal());
  r.bulk = measure(p, 2000, plan.t.diffusion_repeats, 0.05,
                   plan.t.measure_flows ? kDiffusionSpread : 0.0);
  r.with_g = estimate(p, p.temperature, PairDistribution::from_csv(r.bulk.rdf_csv));
}

// The pair parts of the laws at the state point and their powers of T (theory with the measured
// g(r): transport/estimates.hpp).
struct PairParts {
  double kappa, kappa_exponent, eta, eta_exponent;
};
PairParts pair_parts(const Plan& plan, const Results& r) {
  const particle::ParticleParameters& p = plan.p;
  const auto g = PairDistribution::from_csv(r.bulk.rdf_csv);
  const Estimates hotter = estimate(p, 1.1 * p.temperature, g);
  const auto exponent = [](double at, double above) {
    return std::log(above / at) / std::log(1.1);
  };
  return {r.with_g.conductivity_conduction,
          exponent(r.with_g.conductivity_conduction, hotter.conductivity_conduction),
          r.with_g.viscosity_dissipative,
          exponent(r.with_g.viscosity_dissipative, hotter.viscosity_dissipative)};
}

// One set of relaxation runs at `flows`' n and T (its box: Transport/Flow particles at its
// density), as a job for run_jobs, its progress on the console.
Job relaxation_job(const Plan& plan, const PairDistribution& g, particle::ParticleParameters flows,
                   int repeats, RelaxationCoefficients& out, Clock::time_point start) {
  const double edge = std::max(3 * flows.largest_cutoff(),
                               std::pow(plan.t.flow_particles / flows.density, 1.0 / flows.dim));
  flows.box = {{edge, edge, edge}};
  const Estimates guess = estimate(flows, flows.temperature, g);
  const double cost = static_cast<double>(flows.particle_count()) * repeats /
                      (guess.diffusivity * std::pow(2 * M_PI / (2 * edge), 2));
  return {cost, [&out, flows, guess, repeats, start] {
            out = measure_relaxation(
                flows, guess, guess.heat_capacity_p, repeats,
                [&](int done, const RelaxationCoefficients& so_far, int repeat) {
                  const auto &k = so_far.conductivity.value, &e = so_far.viscosity.value;
                  std::printf("transport: relaxation at n = %.4g, T = %.4g, %d/%d runs (N = %ld, "
                              "%ld steps; run %d ended): kappa %.4g +- %.2g, eta %.4g +- %.2g; "
                              "%.0f s\n",
                              flows.density, flows.temperature, done, repeats, so_far.particles,
                              so_far.steps, repeat + 1, k.mean, k.stderr_, e.mean, e.stderr_,
                              seconds_since(start));
                  std::fflush(stdout);
                });
          }};
}

// The heat slabs' job: kappa and its law at the scene's scale (slab_kappa.cpp).
Job slab_job(const Plan& plan, Results& r, Clock::time_point start) {
  const particle::ParticleParameters& p = plan.p;
  // kappa's guess for the slabs' power: the particles' part rho (c_v + k) D with the measured D
  // and the pair part; within ~15% for the default fluid, which sets the span within as much.
  const double cv = p.energy == particle::EnergyModel::Dpde ? p.cv : 0.0;
  const PairParts pairs = pair_parts(plan, r);
  const double guess = p.density * (cv + 1) * r.bulk.diffusion.mean + pairs.kappa;
  const particle::ParticleParameters slab =
      slab_fluid(plan.scene, p, guess, r.with_g.heat_capacity_p);
  std::printf("transport: kappa from periodic heat slabs: %ld particles, %ld + %ld steps\n",
              slab.particle_count(), slab.equilibration_steps, slab.steps);
  std::fflush(stdout);
  return {static_cast<double>(slab.particle_count()) * (slab.steps + slab.equilibration_steps),
          [&plan, &r, start, slab, pairs] {
            r.slab = kappa_from_slabs(slab, plan.p.density, plan.p.temperature, pairs.kappa,
                                      pairs.kappa_exponent, r.bulk.diffusion_exponent.mean);
            std::printf("transport: kappa from the heat slabs = %.4g +- %.2g; %.0f s\n",
                        r.slab.kappa.mean, r.slab.kappa.stderr_, seconds_since(start));
            std::fflush(stdout);
          }};
}

// Step 2: the flow runs, one job each (relaxation at each temperature and at the isobar's ends,
// the heat slabs, the wall run), spread over the cores.
void measure_flows(const Plan& plan, Results& r) {
  const particle::ParticleParameters& p = plan.p;
  const auto measured_g = PairDistribution::from_csv(r.bulk.rdf_csv);
  const auto start = Clock::now();
  std::vector<Job> jobs;
  r.at_temperature.resize(plan.temperatures.size());
  r.at_isobar_ends.resize(plan.isobar_ends.size());
  if (plan.t.measure_flows) {
    if (plan.k_rc > 0.3)
      std::cout << "transport: the relaxation modes have k rc = " << plan.k_rc << " (wavelength "
                << 2 * plan.flow_edge / p.largest_cutoff()
                << " cutoffs): coefficients at that finite wavenumber; more Transport/Flow "
                   "particles lower it (k rc ~ N^(-1/d))\n";
    std::size_t set = 0; // each set its own seeds
    for (std::size_t i = 0; i < plan.temperatures.size(); ++i, ++set) {
      particle::ParticleParameters flows = p;
      flows.temperature = plan.temperatures[i];
      flows.seed = p.seed + 104729 * set;
      jobs.push_back(
          relaxation_job(plan, measured_g, flows, plan.t.flow_repeats, r.at_temperature[i], start));
    }
    // The ends need eta to ~5%, the state point (which sets its value) to ~3%.
    const int end_repeats = std::max(2, plan.t.flow_repeats / 2);
    for (std::size_t j = 0; j < plan.isobar_ends.size(); ++j, ++set) {
      particle::ParticleParameters flows = p;
      std::tie(flows.density, flows.temperature) = plan.isobar_ends[j];
      flows.seed = p.seed + 104729 * set;
      jobs.push_back(
          relaxation_job(plan, measured_g, flows, end_repeats, r.at_isobar_ends[j], start));
    }
  }
  if (plan.slabs) jobs.push_back(slab_job(plan, r, start));
  if (plan.t.kappa_from_walls)
    jobs.push_back({4000.0 * plan.t.wall_steps * 1.2, [&] {
                      r.walls = kappa_from_walls(plan.scene, plan.scene_fluid, p.temperature,
                                                 plan.t.wall_steps);
                    }});
  run_jobs(std::move(jobs));
}

// eta's law through the relaxation runs at the state point (and its temperature spread) and at
// the isobar's ends, P fitted (laws.hpp), where every set has a finite error and the fit gives
// a law positive at every point, a inside its search range and finite errors; otherwise
// r.eta_law is left as it is (theory's pair part), with a message.
void take_isobar_law(const Plan& plan, const PairParts& pairs, Results& r) {
  std::vector<StatePoint> points;
  for (std::size_t i = 0; i < r.at_temperature.size(); ++i)
    points.push_back({plan.p.density, r.measured_at[i], r.at_temperature[i].viscosity.value});
  for (std::size_t j = 0; j < r.at_isobar_ends.size(); ++j) {
    const RelaxationCoefficients& end = r.at_isobar_ends[j];
    const double T = std::isfinite(end.temperature.value.mean) ? end.temperature.value.mean
                                                               : plan.isobar_ends[j].second;
    points.push_back({plan.isobar_ends[j].first, T, end.viscosity.value});
  }
  bool measured = true;
  for (const StatePoint& s : points) measured = measured && s.value.stderr_ > 0;
  if (!measured) { // every fit of a set failed
    std::printf("transport: eta not measured at the isobar's ends: the twin keeps theory's pair "
                "part\n");
    return;
  }
  const CoefficientLaw law =
      fit_law_and_pair(points, plan.p.density, plan.p.temperature, pairs.eta_exponent);
  bool sound = law.K >= 0 && law.P >= 0 && law.a > -2.99 && law.a < 4.99 &&
               std::isfinite(law.K_stderr) && std::isfinite(law.P_stderr) &&
               std::isfinite(law.a_stderr);
  for (const StatePoint& s : points) sound = sound && law.at(s.n, s.T) > 0;
  if (sound) {
    r.eta_law = law;
    return;
  }
  std::printf("transport: eta's law through the isobar's ends is not sound (K %.3g +- %.2g, a %.3g "
              "+- %.2g, P %.3g +- %.2g): the twin keeps theory's pair part\n",
              law.K, law.K_stderr, law.a, law.a_stderr, law.P, law.P_stderr);
}

// Step 3: which kappa and eta the twin takes, and their laws c(n, T).
void choose_coefficients(const Plan& plan, Results& r) {
  const particle::ParticleParameters& p = plan.p;
  const std::size_t mid = plan.temperatures.size() / 2;
  r.measured_at = plan.temperatures;
  for (std::size_t i = 0; i < r.at_temperature.size(); ++i)
    if (std::isfinite(r.at_temperature[i].temperature.value.mean))
      r.measured_at[i] = r.at_temperature[i].temperature.value.mean;
  r.state_temperature = plan.t.measure_flows ? r.measured_at[mid] : p.temperature;
  if (plan.t.measure_flows) {
    r.flow = r.at_temperature[mid];
    r.kappa = r.flow.conductivity.value;
    r.eta = r.flow.viscosity.value;
  }
  if (plan.t.kappa_from_walls) r.kappa = r.walls.kappa;
  if (r.at_temperature.size() > 1) {
    std::vector<particle::Estimate> k, e;
    for (const auto& a : r.at_temperature)
      k.push_back(a.conductivity.value), e.push_back(a.viscosity.value);
    r.kappa_power = fit_power_law(r.measured_at, k, r.state_temperature);
    r.eta_power = fit_power_law(r.measured_at, e, r.state_temperature);
  }
  if (!plan.t.measure_flows) return;
  // The laws (laws.hpp): eta's through the state point and the isobar's ends where measured,
  // else its particle part goes as D (eta_K = rho m D / 2) and its pair part as theory's;
  // kappa's from the slabs' profile where measured, else through the relaxation value with D's
  // power of T.
  const PairParts pairs = pair_parts(plan, r);
  const particle::Estimate a_D = r.bulk.diffusion_exponent;
  r.eta_law = law_through(r.eta, r.state_temperature, p.density, p.temperature, pairs.eta,
                          pairs.eta_exponent, a_D.mean, a_D.stderr_);
  if (!plan.isobar_ends.empty()) take_isobar_law(plan, pairs, r);
  if (plan.slabs) {
    r.kappa_law = r.slab.law;
    r.kappa = {r.kappa_law.at(p.density, p.temperature), r.kappa_law.K_stderr};
  } else {
    r.kappa_law = law_through(r.kappa, r.state_temperature, p.density, p.temperature, pairs.kappa,
                              pairs.kappa_exponent, a_D.mean, a_D.stderr_);
  }
  r.has_laws = std::isfinite(r.kappa_law.K) && std::isfinite(r.eta_law.K);
}

// coefficients.csv's rows of the coefficients measured away from the state point and of the laws
// fitted through them; row(name, estimate_g1, estimate_measured_g, measured, stderr).
template <class Row> void away_from_state_point_rows(const Plan& plan, const Results& r, Row& row) {
  const double nan = std::nan("");
  if (r.at_temperature.size() > 1) {
    for (std::size_t i = 0; i < plan.temperatures.size(); ++i) {
      char at[32];
      std::snprintf(at, sizeof at, "_at_T_%.4g", r.measured_at[i]);
      row("viscosity_eta" + std::string(at), nan, nan, r.at_temperature[i].viscosity.value.mean,
          r.at_temperature[i].viscosity.value.stderr_);
      row("conductivity_kappa" + std::string(at), nan, nan,
          r.at_temperature[i].conductivity.value.mean,
          r.at_temperature[i].conductivity.value.stderr_);
    }
    row("viscosity_exponent_n_in_T^n", nan, nan, r.eta_power.exponent, r.eta_power.exponent_stderr);
    row("conductivity_exponent_n_in_T^n", nan, nan, r.kappa_power.exponent,
        r.kappa_power.exponent_stderr);
  }
  for (std::size_t j = 0; j < r.at_isobar_ends.size(); ++j) {
    char at[48];
    std::snprintf(at, sizeof at, "_at_n_%.4g_T_%.4g", plan.isobar_ends[j].first,
                  plan.isobar_ends[j].second);
    const RelaxationCoefficients& end = r.at_isobar_ends[j];
    row("viscosity_eta" + std::string(at), nan, nan, end.viscosity.value.mean,
        end.viscosity.value.stderr_);
    row("conductivity_kappa" + std::string(at), nan, nan, end.conductivity.value.mean,
        end.conductivity.value.stderr_);
  }
  if (r.has_laws) {
    row("conductivity_law_K", nan, nan, r.kappa_law.K, r.kappa_law.K_stderr);
    row("conductivity_law_a", nan, nan, r.kappa_law.a, r.kappa_law.a_stderr);
    row("conductivity_law_P", nan, r.with_g.conductivity_conduction, r.kappa_law.P, nan);
    row("viscosity_law_K", nan, nan, r.eta_law.K, r.eta_law.K_stderr);
    row("viscosity_law_a", nan, nan, r.eta_law.a, r.eta_law.a_stderr);
    row("viscosity_law_P", nan, r.with_g.viscosity_dissipative, r.eta_law.P,
        r.eta_law.has_covariance ? r.eta_law.P_stderr : nan); // else theory's
  }
}

// coefficients.csv: the estimates beside the measurements, one row per coefficient.
std::string coefficients_table(const Plan& plan, const Results& r) {
  const particle::ParticleParameters& p = plan.p;
  const double nan = std::nan("");
  std::ostringstream table;
  char line[256];
  std::snprintf(line, sizeof line,
                "# state point: rho = %g, T = %g (%dD periodic box, N = %ld); kappa and eta "
                "measured at T = %.4g (the relaxation runs' own)\n",
                p.density, p.temperature, p.dim, p.particle_count(), r.state_temperature);
  table << line
        << "coefficient,estimate_g1,estimate_measured_g,measured,measured_stderr,"
           "measured/estimate\n";
  auto row = [&](const std::string& name, double e1, double eg, double meas, double se) {
    std::snprintf(line, sizeof line, "%s,%.6g,%.6g,%.6g,%.3g,%.4f\n", name.c_str(), e1, eg, meas,
                  se, std::isnan(meas) ? NAN : meas / eg);
    table << line;
  };
  const Estimates &ideal = r.ideal, &with_g = r.with_g;
  const Measured& m = r.bulk;
  row("self_diffusion_D", ideal.diffusion, with_g.diffusion, m.diffusion.mean, m.diffusion.stderr_);
  row("viscosity_eta", ideal.viscosity, with_g.viscosity, r.eta.mean, r.eta.stderr_);
  row("conductivity_kappa", ideal.conductivity, with_g.conductivity, r.kappa.mean, r.kappa.stderr_);
  away_from_state_point_rows(plan, r, row);
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
  return table.str();
}

// The twins' equation of state (transport/coefficients.cpp): the ideal fluid's without a
// conservative force (exact; the fit's b0, b1, b2 are then noise about 0), else the fit.
io::Json equation_of_state(const Plan& plan, const Results& r) {
  io::Json eos = io::Json::object();
  const bool ideal_fluid = plan.p.conservative == particle::ConservativeForce::None;
  eos["form"] = "p = n k T + n^2 (b0 + b1 k T + b2 (n - n_ref))";
  eos["n_ref"] = plan.p.density;
  eos["source"] = ideal_fluid ? "ideal DPDE fluid (no conservative force)"
                              : "fit to the bulk runs (measured/excess_pressure)";
  const ExcessPressureFit& fit = r.bulk.excess_pressure;
  for (const auto& [key, value] : {std::pair{"b0", fit.b0},
                                   {"b0_stderr", fit.b0_stderr},
                                   {"b1", fit.b1},
                                   {"b1_stderr", fit.b1_stderr},
                                   {"b2", fit.b2},
                                   {"b2_stderr", fit.b2_stderr}})
    eos[key] = ideal_fluid ? 0.0 : value;
  return eos;
}

// The relaxation runs: method, box and each temperature's repeats (with a temperature spread).
io::Json relaxation_json(const Plan& plan, const Results& r) {
  io::Json method = io::Json::object();
  method["method"] = "heat and transverse-momentum modes decaying in a periodic box (seed 004)";
  method["particles"] = r.flow.particles;
  method["wavenumber_times_cutoff"] = plan.k_rc;
  method["steps"] = r.flow.steps;
  method["conductivity"] = r.flow.conductivity.json();
  method["viscosity"] = r.flow.viscosity.json();
  return method;
}

// The relaxation runs at the isobar's ends (eta's law goes through them).
io::Json isobar_ends_json(const Plan& plan, const Results& r) {
  io::Json ends = io::Json::array();
  for (std::size_t j = 0; j < r.at_isobar_ends.size(); ++j) {
    io::Json end = io::Json::object();
    end["density"] = plan.isobar_ends[j].first;
    end["wall_temperature"] = plan.isobar_ends[j].second;
    end["temperature"] = r.at_isobar_ends[j].temperature.json();
    end["viscosity"] = r.at_isobar_ends[j].viscosity.json();
    end["conductivity"] = r.at_isobar_ends[j].conductivity.json();
    ends.push_back(end);
  }
  return ends;
}

// The relaxation runs at the state point's temperatures and the power laws through them.
void add_temperature_dependence(const Plan& plan, const Results& r, io::Json& measured) {
  io::Json law = io::Json::object();
  law["reference_temperature"] = r.state_temperature;
  law["temperatures"] = io::Json::array();
  law["conductivity"] = io::Json::array();
  law["viscosity"] = io::Json::array();
  for (std::size_t i = 0; i < plan.temperatures.size(); ++i) {
    law["temperatures"].push_back(r.measured_at[i]);
    law["conductivity"].push_back(r.at_temperature[i].conductivity.json());
    law["viscosity"].push_back(r.at_temperature[i].viscosity.json());
  }
  law["conductivity_chi2_per_dof"] = r.kappa_power.chi2_per_dof;
  law["viscosity_chi2_per_dof"] = r.eta_power.chi2_per_dof;
  measured["temperature_dependence"] = law;
  measured["conductivity_exponent"] = r.kappa_power.exponent;
  measured["conductivity_exponent_stderr"] = r.kappa_power.exponent_stderr;
  measured["viscosity_exponent"] = r.eta_power.exponent;
  measured["viscosity_exponent_stderr"] = r.eta_power.exponent_stderr;
}

std::string conductivity_note(const Plan& plan, const Results& r) {
  std::ostringstream note; // the ideal fluid's c_p = c_v + k + (d/2 + 1) k (000:(3.21))
  note << "relaxation: kappa = rho c_p chi with the ideal fluid's c_p = "
       << r.with_g.heat_capacity_p << " k per particle; the relaxation box holds ~"
       << plan.t.flow_particles
       << " particles (x2): in 2D its coefficients depend on the box (long-time tails). Errors: "
          "the larger of the repeats' spread and the fits' own errors, over sqrt(repeats)";
  if (plan.slabs)
    note << "; the twin's kappa is the heat slabs' (the scene's scale, no walls), its law "
            "conductivity_law";
  return note.str();
}

// summary.json's "results" ("measured/conductivity" and "viscosity" are what the twin reads,
// with their laws: transport/coefficients.cpp).
io::Json results_json(const Plan& plan, const Results& r) {
  const TransportParameters& t = plan.t;
  io::Json out = io::Json::object();
  out["state_point"]["density"] = plan.p.density;
  out["state_point"]["temperature"] = plan.p.temperature;
  // The temperature the measured kappa and eta belong to (the relaxation runs' own).
  out["state_point"]["measured_temperature"] = r.state_temperature;
  out["estimated_g1"] = r.ideal.json();
  out["estimated_measured_g"] = r.with_g.json();
  out["measured"] = r.bulk.json();
  out["equation_of_state"] = equation_of_state(plan, r);
  io::Json& measured = out["measured"];
  if (t.kappa_from_walls || t.measure_flows) {
    measured["conductivity"] = r.kappa.mean;
    measured["conductivity_stderr"] = r.kappa.stderr_;
  }
  if (t.kappa_from_walls) measured["walls"] = r.walls.json;
  if (plan.slabs) measured["slabs"] = r.slab.json;
  if (!t.measure_flows) return out;
  if (t.kappa_from_walls || plan.slabs) {
    measured["conductivity_relaxation"] = r.flow.conductivity.value.mean;
    measured["conductivity_relaxation_stderr"] = r.flow.conductivity.value.stderr_;
  }
  measured["viscosity"] = r.eta.mean;
  measured["viscosity_stderr"] = r.eta.stderr_;
  measured["relaxation"] = relaxation_json(plan, r);
  if (r.has_laws) {
    measured["conductivity_law"] = r.kappa_law.json();
    measured["viscosity_law"] = r.eta_law.json();
  }
  if (!r.at_isobar_ends.empty()) measured["isobar_ends"] = isobar_ends_json(plan, r);
  if (r.at_temperature.size() > 1) add_temperature_dependence(plan, r, measured);
  measured["conductivity_note"] = conductivity_note(plan, r);
  return out;
}
} // namespace

TransportMeasurement measure_transport(const scene::SceneParameters& scene,
                                       const particle::ParticleParameters& scene_fluid,
                                       const particle::ParticleParameters& p,
                                       const TransportParameters& t) {
  const Plan plan = make_plan(scene, scene_fluid, p, t);
  Results r;
  measure_bulk(plan, r);
  measure_flows(plan, r);
  choose_coefficients(plan, r);
  TransportMeasurement out;
  out.results = results_json(plan, r);
  out.coefficients_csv = coefficients_table(plan, r);
  out.rdf_csv = r.bulk.rdf_csv;
  return out;
}

} // namespace twinflow::transport
