// twinflow transport CASE: the fluid's coefficients at the case's state point, estimated from
// theory (g = 1 and measured g(r)) and measured by short periodic particle runs, side by side.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <unistd.h>

#include "app/case/case.hpp"
#include "app/commands.hpp"
#include "transport/estimates.hpp"
#include "transport/measure.hpp"

namespace twinflow::app {

namespace fs = std::filesystem;

namespace {
// What the transport stage's outputs depend on: the fluid (the Particle section, less the scene's
// run lengths and walls), the dimension, the state point and the measurement settings; not the
// scene's box, walls or gravity; the method's version (kTransportMethod).
io::Json measurement_inputs(const Case& c, const particle::ParticleParameters& p,
                            const TransportParameters& t) {
  io::Json j = io::Json::object();
  const io::Json resolved = c.registry().resolved_json();
  for (const auto& [path, value] : resolved.items()) {
    const bool fluid = path.rfind("Particle/", 0) == 0 && path.rfind("Particle/Walls/", 0) != 0 &&
                       path != "Particle/Steps" && path != "Particle/Equilibration steps" &&
                       path != "Particle/Initial velocities" &&
                       path != "Particle/Initial internal energy";
    if (fluid) j[path] = value;
  }
  j["dimension"] = p.dim;
  j["start"] = "equilibrium"; // bulk runs start at (c_v + k) T whatever the case says
  j["density"] = p.density;
  j["temperature"] = p.temperature;
  j["measure_flows"] = t.measure_flows;
  if (t.measure_flows) {
    j["flow_particles"] = t.flow_particles;
    j["flow_repeats"] = t.flow_repeats;
    j["temperature_spread"] = t.temperature_spread;
  }
  j["method"] = kTransportMethod;
  if (t.kappa_from_walls) { // the scene and the particle walls enter the wall run
    for (const auto& [path, value] : resolved.items())
      if (path.rfind("Scene/", 0) == 0 || path.rfind("Particle/Walls/", 0) == 0) j[path] = value;
    j["kappa_from_walls"] = true;
    j["wall_steps"] = t.wall_steps;
  }
  return j;
}

// Bulk measurements are cached across run directories under the hash of their inputs, so sweeps
// and reruns do not redo them: $TWINFLOW_CACHE/transport/HASH (default $XDG_CACHE_HOME/twinflow,
// else ~/.cache/twinflow; TWINFLOW_CACHE=off disables it). Empty: no cache.
fs::path cache_directory(const std::string& hash) {
  const char* env = std::getenv("TWINFLOW_CACHE");
  fs::path root;
  if (env && *env) {
    if (std::string(env) == "off") return {};
    root = env;
  } else if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    root = fs::path(xdg) / "twinflow";
  } else if (const char* home = std::getenv("HOME"); home && *home) {
    root = fs::path(home) / ".cache" / "twinflow";
  } else {
    return {};
  }
  return root / "transport" / hash;
}

const char* kCachedFiles[] = {"coefficients.csv", "rdf.csv", "summary.json"};

// Copies a cached result into the stage, with this case's name and parameters. False: no entry
// (or an unreadable one: the cache is a convenience, never a reason to fail).
bool restore_from_cache(const fs::path& entry, const io::StageDirectory& stage, const Case& c,
                        const std::string& name) {
  for (const char* f : kCachedFiles)
    if (!fs::exists(entry / f)) return false;
  io::Json summary;
  try {
    summary = io::read_json(entry / "summary.json");
  } catch (const std::exception& e) {
    std::cerr << "transport: cache entry " << entry.string() << " unreadable (" << e.what()
              << "): measuring\n";
    return false;
  }
  const io::Json* made_by = io::find(summary, {"provenance"});
  if (!made_by) return false; // not an entry this code wrote
  const io::Json* revision = io::find(*made_by, {"twinflow_git_revision"});
  const io::Json now = io::provenance();
  if (revision && *revision != now.at("twinflow_git_revision"))
    std::cout << "transport: the cached measurements were made by twinflow " << revision->dump()
              << " (this is " << now.at("twinflow_git_revision").dump()
              << "); --force or TWINFLOW_CACHE=off measures again\n";
  io::Json cache = io::Json::object();
  cache["entry"] = entry.string();
  cache["made_by"] = *made_by;
  summary["cache"] = cache;
  summary["case"] = name;
  summary["provenance"] = io::provenance();
  summary["parameters"] = c.registry().resolved_json();
  stage.create();
  io::write_file_atomically(stage.file("coefficients.csv"),
                            io::read_file(entry / "coefficients.csv"));
  io::write_file_atomically(stage.file("rdf.csv"), io::read_file(entry / "rdf.csv"));
  io::write_file_atomically(stage.file("summary.json"), io::dump(summary));
  return true;
}
// Transport/Kappa from walls: conduction between the scene's thermal walls of its heated
// direction (theirs: temperatures, slip, Particle/Walls), periodic across, no gravity, ~4000
// particles. kappa = the walls' mean heat flux / |slope| of the central 60% (particle/run.cpp's
// wall_profile): Fourier's law over the scene's own temperature span.
struct WallKappa {
  particle::Estimate kappa{std::nan(""), std::nan("")};
  io::Json json = io::Json::object();
};
WallKappa kappa_from_walls(const CaseParameters& cp, const particle::ParticleParameters& fluid,
                           long steps) {
  const int heated = heated_direction(cp.scene);
  if (heated < 0)
    throw io::InputError("Transport/Kappa from walls = true needs two thermal walls at different "
                         "temperatures in one direction of the scene");
  particle::ParticleParameters w = cp.particle; // the scene's walls and fluid
  w.temperature = fluid.temperature;
  w.initial_velocities = particle::InitialVelocities::Maxwell;
  w.initial_internal_energy = particle::InitialInternalEnergy::Equilibrium;
  w.temperature_perturbation = 0, w.shear_perturbation = 0, w.poiseuille_force = 0;
  w.gravity = {{0, 0, 0}};
  w.heat_slabs.clear();
  const double length = w.box[heated];
  const double across = std::max(
      3 * w.largest_cutoff(), std::pow(4000 / (w.density * length), 1.0 / std::max(1, w.dim - 1)));
  for (int d = 0; d < w.dim; ++d) {
    w.bins[d] = 1;
    if (d == heated) continue;
    w.walls[d].present = false;
    w.box[d] = across;
  }
  w.bins[heated] = std::max(10, static_cast<int>(std::lround(2 * length / w.largest_cutoff())));
  w.steps = steps;
  w.equilibration_steps = steps / 5;
  w.seed = fluid.seed + 7919;
  const auto start = std::chrono::steady_clock::now();
  std::printf("transport: kappa from the walls: %ld particles, %ld + %ld steps\n",
              w.particle_count(), w.equilibration_steps, w.steps);
  std::fflush(stdout);
  particle::RunControl control;
  control.progress = isatty(STDERR_FILENO); // a progress line with ETA on a terminal only
  const particle::RunOutput out = particle::run_particles(w, control);
  const auto lower = wall_name(heated, 0), upper = wall_name(heated, 1);
  const double q_lo = io::number(out.summary, {"walls", lower.c_str(), "heat_flux_in"});
  const double q_up = io::number(out.summary, {"walls", upper.c_str(), "heat_flux_in"});
  const double se_q =
      0.5 * std::hypot(largest_stderr(out.summary, lower), largest_stderr(out.summary, upper));
  const double q = 0.5 * (q_lo - q_up); // from the lower wall to the upper one
  // Steady: both walls carry the same flow. Else the profile is still forming.
  const double imbalance = (q_lo + q_up) / (2 * se_q);
  if (std::fabs(imbalance) > 3)
    std::printf("transport: kappa from the walls: the walls' heat flows differ by %.1f standard "
                "errors (%.4g in, %.4g out): not yet steady; raise Transport/Wall steps\n",
                std::fabs(imbalance), q_lo, -q_up);
  const double slope = io::number(out.summary, {"wall_profile", "slope"}),
               se_slope = io::number(out.summary, {"wall_profile", "slope_stderr"});
  WallKappa r;
  r.kappa.mean = -q / slope; // Fourier: q = -kappa dT/dx
  r.kappa.stderr_ = std::fabs(r.kappa.mean) * std::hypot(se_q / q, se_slope / slope);
  r.json["method"] = "conduction between the scene's thermal walls (Fourier's law)";
  r.json["particles"] = w.particle_count();
  r.json["box"] = io::Json::array();
  for (int d = 0; d < w.dim; ++d) r.json["box"].push_back(w.box[d]);
  r.json["steps"] = w.steps;
  r.json["heat_flux"] = q, r.json["heat_flux_stderr"] = se_q;
  r.json["heat_flux_walls"] = io::Json::array();
  r.json["heat_flux_walls"].push_back(q_lo), r.json["heat_flux_walls"].push_back(-q_up);
  r.json["wall_imbalance_over_stderr"] = imbalance;
  r.json["slope"] = slope, r.json["slope_stderr"] = se_slope;
  r.json["conductivity"] = r.kappa.mean, r.json["conductivity_stderr"] = r.kappa.stderr_;
  r.json["T_internal"] = io::number(out.summary, {"T_internal"});
  if (const io::Json* profile = io::find(out.summary, {"wall_profile"}))
    r.json["wall_profile"] = *profile;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.json["seconds"] = seconds;
  std::printf("transport: kappa from the walls = %.4g +- %.2g (flux %.4g +- %.2g, slope %.4g +- "
              "%.2g); %.0f s\n",
              r.kappa.mean, r.kappa.stderr_, q, se_q, slope, se_slope, seconds);
  return r;
}
} // namespace

int transport_stage(const CommandLine& cl) {
  Case c;
  const CaseParameters cp = c.load(cl.target, cl.overrides);
  const fs::path run_dir = cl.out.empty() ? fs::path("twinflow-runs") / cp.name : fs::path(cl.out);
  const io::StageDirectory stage(run_dir, "transport", cl.force);
  // Bulk coefficients: a periodic box at the scene's density and mean temperature, at least
  // ~4000 particles (cubic or square), whatever the scene's own boundaries.
  particle::ParticleParameters p = cp.particle;
  double wall_mean = 0;
  int walls = 0;
  for (int d = 0; d < cp.scene.dim; ++d)
    if (!cp.scene.boundary[d].periodic)
      for (int s = 0; s < 2; ++s)
        if (cp.scene.boundary[d].thermal[s])
          wall_mean += cp.scene.boundary[d].temperature[s], ++walls;
  if (walls > 0) p.temperature = wall_mean / walls;
  if (cp.transport.temperature > 0) p.temperature = cp.transport.temperature;
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

  const io::Json key_inputs = measurement_inputs(c, p, cp.transport);
  const std::string key = io::content_hash(key_inputs.dump());
  const fs::path cache = cache_directory(key);
  // --force measures again (and refreshes the entry).
  if (!cache.empty() && !cl.force && restore_from_cache(cache, stage, c, cp.name)) {
    std::cout << io::read_file(stage.file("coefficients.csv"))
              << "transport: measurements reused from the cache (" << cache.string()
              << "; TWINFLOW_CACHE=off recomputes)\noutputs: "
              << fs::absolute(stage.path()).string() << "\n";
    return 0;
  }
  stage.create();

  const double nan = std::nan("");
  const transport::Estimates ideal =
      transport::estimate(p, p.temperature, transport::PairDistribution::ideal());
  const long steps = 2000;
  const transport::Measured m = transport::measure(p, steps);
  const auto measured_g = transport::PairDistribution::from_csv(m.rdf_csv);
  const transport::Estimates with_g = transport::estimate(p, p.temperature, measured_g);
  particle::Estimate kappa{nan, nan}, eta{nan, nan};
  transport::RelaxationCoefficients flow;
  // With a temperature spread s, also at T (1 -+ s): kappa(T) and eta(T) as power laws.
  std::vector<double> temperatures{p.temperature};
  const double spread = cp.transport.temperature_spread;
  if (spread > 0)
    temperatures = {p.temperature * (1 - spread), p.temperature, p.temperature * (1 + spread)};
  std::vector<transport::RelaxationCoefficients> at_temperature;
  // The relaxation runs' own, smaller box: they last a few relaxation times of the box, ~ L^2.
  const double flow_edge = std::max(3 * p.largest_cutoff(),
                                    std::pow(cp.transport.flow_particles / p.density, 1.0 / p.dim));
  // The modes' wavelength is the doubled box edge; hydrodynamics needs it long against the
  // interaction range (k rc << 1), else the coefficients are those of a finite wavenumber.
  const double k_rc = 2 * M_PI / (2 * flow_edge) * p.largest_cutoff();
  if (cp.transport.measure_flows) {
    // c_p per particle: the ideal fluid's for the ideal gas (estimate); with conservative forces
    // the same is an approximation (the measured c_p - c_v is reported beside it).
    particle::ParticleParameters flows = p;
    flows.box = {{flow_edge, flow_edge, flow_edge}};
    const int repeats = cp.transport.flow_repeats;
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
      const transport::Estimates guess = transport::estimate(flows, t, measured_g);
      at_temperature.push_back(transport::measure_relaxation(
          flows, guess, guess.heat_capacity_p, repeats,
          [&](int done, const transport::RelaxationCoefficients& so_far) {
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
  if (cp.transport.kappa_from_walls) {
    by_walls = kappa_from_walls(cp, p, cp.transport.wall_steps);
    kappa = by_walls.kappa;
  }
  // The relaxation runs' own temperatures (the state they measured), where known.
  std::vector<double> measured_at = temperatures;
  for (std::size_t i = 0; i < at_temperature.size(); ++i)
    if (std::isfinite(at_temperature[i].temperature.value.mean))
      measured_at[i] = at_temperature[i].temperature.value.mean;
  const double state_temperature =
      at_temperature.empty() ? p.temperature : measured_at[temperatures.size() / 2];
  transport::PowerLawFit kappa_law, eta_law;
  if (at_temperature.size() > 1) {
    std::vector<particle::Estimate> k, e;
    for (const auto& a : at_temperature)
      k.push_back(a.conductivity.value), e.push_back(a.viscosity.value);
    kappa_law = transport::fit_power_law(measured_at, k, state_temperature);
    eta_law = transport::fit_power_law(measured_at, e, state_temperature);
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
  row("heat_capacity_cv_per_particle", ideal.heat_capacity_v, with_g.heat_capacity_v, nan, nan);
  row("heat_capacity_cp_per_particle", ideal.heat_capacity_p, with_g.heat_capacity_p, nan, nan);
  row("heat_capacity_cp_minus_cv_per_particle", ideal.heat_capacity_p - ideal.heat_capacity_v,
      with_g.heat_capacity_p - with_g.heat_capacity_v, m.cp_minus_cv.mean, m.cp_minus_cv.stderr_);
  row("prandtl", ideal.prandtl, with_g.prandtl, nan, nan);
  row("schmidt", ideal.schmidt, with_g.schmidt, nan, nan);
  io::write_file_atomically(stage.file("coefficients.csv"), table.str());
  io::write_file_atomically(stage.file("rdf.csv"), m.rdf_csv);

  io::Json summary = io::Json::object();
  summary["stage"] = "transport";
  summary["case"] = cp.name;
  summary["provenance"] = io::provenance();
  summary["parameters"] = c.registry().resolved_json();
  summary["results"]["state_point"]["density"] = p.density;
  summary["results"]["state_point"]["temperature"] = p.temperature;
  // The temperature the measured kappa and eta belong to (the relaxation runs' own).
  summary["results"]["state_point"]["measured_temperature"] = state_temperature;
  summary["results"]["estimated_g1"] = ideal.json();
  summary["results"]["estimated_measured_g"] = with_g.json();
  summary["results"]["measured"] = m.json();
  // The continuum twin reads "conductivity" and "viscosity" (app/continuum_stage.cpp).
  if (cp.transport.kappa_from_walls || cp.transport.measure_flows) {
    summary["results"]["measured"]["conductivity"] = kappa.mean;
    summary["results"]["measured"]["conductivity_stderr"] = kappa.stderr_;
  }
  if (cp.transport.kappa_from_walls) summary["results"]["measured"]["walls"] = by_walls.json;
  if (cp.transport.measure_flows) {
    if (cp.transport.kappa_from_walls) {
      summary["results"]["measured"]["conductivity_relaxation"] = flow.conductivity.value.mean;
      summary["results"]["measured"]["conductivity_relaxation_stderr"] =
          flow.conductivity.value.stderr_;
    }
    summary["results"]["measured"]["viscosity"] = eta.mean;
    summary["results"]["measured"]["viscosity_stderr"] = eta.stderr_;
    io::Json method = io::Json::object();
    method["method"] = "heat and transverse-momentum modes decaying in a periodic box (seed 004)";
    method["particles"] = flow.particles;
    method["wavenumber_times_cutoff"] = k_rc;
    method["steps"] = flow.steps;
    method["conductivity"] = flow.conductivity.json();
    method["viscosity"] = flow.viscosity.json();
    summary["results"]["measured"]["relaxation"] = method;
    if (at_temperature.size() > 1) {
      // The continuum twin reads the exponents (app/continuum_stage.cpp).
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
      summary["results"]["measured"]["temperature_dependence"] = law;
      summary["results"]["measured"]["conductivity_exponent"] = kappa_law.exponent;
      summary["results"]["measured"]["conductivity_exponent_stderr"] = kappa_law.exponent_stderr;
      summary["results"]["measured"]["viscosity_exponent"] = eta_law.exponent;
      summary["results"]["measured"]["viscosity_exponent_stderr"] = eta_law.exponent_stderr;
    }
    std::ostringstream note; // the ideal fluid's c_p = c_v + k + (d/2 + 1) k (000:(3.21))
    note << "kappa = rho c_p chi with the ideal fluid's c_p = " << with_g.heat_capacity_p
         << " k per particle; the relaxation box holds ~" << cp.transport.flow_particles
         << " particles (x2): in 2D its coefficients depend on the box (long-time tails). Errors: "
            "the larger of the repeats' spread and the fits' own errors, over sqrt(repeats)";
    summary["results"]["measured"]["conductivity_note"] = note.str();
  }
  summary["measurement_key"] = key;
  io::write_file_atomically(stage.file("summary.json"), io::dump(summary));
  if (!cache.empty()) {
    // summary.json last: an interrupted copy leaves no entry. Best effort (read-only home, full
    // disk): the stage's own results are already written.
    try {
      fs::create_directories(cache);
      io::write_file_atomically(cache / "inputs.json", io::dump(key_inputs));
      io::write_file_atomically(cache / "coefficients.csv", table.str());
      io::write_file_atomically(cache / "rdf.csv", m.rdf_csv);
      io::write_file_atomically(cache / "summary.json", io::dump(summary));
    } catch (const std::exception& e) {
      std::cerr << "transport: not cached (" << e.what() << ")\n";
    }
  }
  std::cout << table.str() << "outputs: " << fs::absolute(stage.path()).string() << "\n";
  return 0;
}

} // namespace twinflow::app
