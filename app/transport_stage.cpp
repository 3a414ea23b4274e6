// twinflow transport CASE: the fluid's coefficients at the case's state point, estimated from
// theory (g = 1 and measured g(r)) and measured by short periodic particle runs, side by side.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "app/case/case.hpp"
#include "app/commands.hpp"
#include "transport/estimates.hpp"
#include "transport/measure.hpp"

namespace twinflow::app {

namespace fs = std::filesystem;

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
  // that starts at rest would otherwise measure at a lower temperature).
  p.initial_velocities = particle::InitialVelocities::Maxwell;
  p.temperature_perturbation = 0;
  p.poiseuille_force = 0;
  p.gravity = {{0, 0, 0}};
  for (auto& w : p.walls) w.present = false;
  p.heat_slabs.clear();
  const double edge = std::max(3 * p.largest_cutoff(), std::pow(4000 / p.density, 1.0 / p.dim));
  p.box = {{edge, edge, edge}};
  stage.create();

  const double nan = std::nan("");
  const transport::Estimates ideal =
      transport::estimate(p, p.temperature, transport::PairDistribution::ideal());
  const long steps = 2000;
  const transport::Measured m = transport::measure(p, steps);
  const transport::Estimates with_g =
      transport::estimate(p, p.temperature, transport::PairDistribution::from_csv(m.rdf_csv));
  particle::Estimate kappa{nan, nan}, eta{nan, nan};
  if (cp.transport.measure_flows) {
    // c_p per particle: the ideal fluid's for the ideal gas (estimate); with conservative forces
    // the same is an approximation (c_p - c_v from the measured equation of state is not yet
    // used), stated in the summary.
    // Their own, smaller box: both runs last a few relaxation times of the box, ~ L^2.
    particle::ParticleParameters flows = p;
    const double flow_edge = std::max(
        3 * p.largest_cutoff(), std::pow(cp.transport.flow_particles / p.density, 1.0 / p.dim));
    flows.box = {{flow_edge, flow_edge, flow_edge}};
    kappa = transport::measure_conductivity_relaxation(flows, with_g, with_g.heat_capacity_p);
    eta = transport::measure_viscosity_poiseuille(flows, with_g);
  }

  std::ostringstream table;
  char line[256];
  std::snprintf(line, sizeof line, "# state point: rho = %g, T = %g (%dD periodic box, N = %ld)\n",
                p.density, p.temperature, p.dim, p.particle_count());
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
  row("conductivity_kappa_002_eq22", ideal.conductivity_002_eq22, with_g.conductivity_002_eq22, nan,
      nan);
  row("thermal_expansion_alpha", ideal.expansion, with_g.expansion, m.expansion.mean,
      m.expansion.stderr_);
  row("pressure_ideal_gas", p.density * p.temperature, p.density * p.temperature, m.pressure.mean,
      m.pressure.stderr_);
  row("heat_capacity_cv_per_particle", ideal.heat_capacity_v, with_g.heat_capacity_v, nan, nan);
  row("heat_capacity_cp_per_particle", ideal.heat_capacity_p, with_g.heat_capacity_p, nan, nan);
  row("prandtl", ideal.prandtl, with_g.prandtl, nan, nan);
  row("schmidt", ideal.schmidt, with_g.schmidt, nan, nan);
  io::write_file_atomically(stage.file("coefficients.csv"), table.str());
  io::write_file_atomically(stage.file("rdf.csv"), m.rdf_csv);

  io::Json summary = io::Json::object();
  summary["stage"] = "transport";
  summary["case"] = cp.name;
  summary["provenance"] = io::provenance();
  summary["parameters"] = c.registry().resolved_json();
  summary["results"]["estimated_g1"] = ideal.json();
  summary["results"]["estimated_measured_g"] = with_g.json();
  summary["results"]["measured"] = m.json();
  if (cp.transport.measure_flows) {
    summary["results"]["measured"]["conductivity_relaxation"] = kappa.mean;
    summary["results"]["measured"]["conductivity_relaxation_stderr"] = kappa.stderr_;
    std::ostringstream note; // the ideal fluid's c_p = c_v + k + (d/2 + 1) k (000:(3.21))
    note << "kappa = rho c_p chi with the ideal fluid's c_p = " << with_g.heat_capacity_p
         << " k per particle; the relaxation and Poiseuille boxes hold ~"
         << cp.transport.flow_particles
         << " particles (x2): in 2D their coefficients depend on the box (long-time tails)";
    summary["results"]["measured"]["conductivity_note"] = note.str();
    summary["results"]["measured"]["viscosity_poiseuille"] = eta.mean;
    summary["results"]["measured"]["viscosity_poiseuille_stderr"] = eta.stderr_;
  }
  io::write_file_atomically(stage.file("summary.json"), summary.dump());
  std::cout << table.str() << "outputs: " << fs::absolute(stage.path()).string() << "\n";
  return 0;
}

} // namespace twinflow::app
