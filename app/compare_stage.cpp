// twinflow compare RUNDIR: the distance between the particle run and its continuum twins
// (nominal, calibrated), results in RUNDIR/compare. Also the calibrated twin's wall conditions.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "app/case/case.hpp"
#include "app/commands.hpp"
#include "compare/twin_distance.hpp"
#include "io/files.hpp"

namespace twinflow::app {

namespace fs = std::filesystem;

namespace {

// What compare needs of a finished particle run.
struct ParticleRun {
  io::Json summary;
  CaseParameters parameters;
  io::FieldFile::Contents fields;
  std::vector<std::vector<double>> temperature_blocks; // blocks.csv (runs before it: empty)
  std::array<bool, 3> walled{{false, false, false}};
  // The final averages, with the per-block temperatures behind them.
  compare::BinnedState final_state() const {
    compare::BinnedState s = compare::particle_state(fields.grid, fields.snapshots.back());
    s.temperature_blocks = temperature_blocks;
    return s;
  }
};

ParticleRun load_particle_run(const fs::path& run_dir, const std::vector<std::string>& overrides) {
  ParticleRun r;
  const fs::path dir = run_dir / "particle";
  r.summary = io::read_json(dir / "summary.json",
                            "the particle stage has not finished in " + run_dir.string() +
                                " (twinflow run CASE --out " + run_dir.string() + ")");
  Case c;
  r.parameters =
      c.load_resolved(r.summary.at("parameters"), io::text(r.summary, {"case"}), overrides);
  if (!fs::exists(dir / "fields.h5"))
    throw io::InputError((dir / "fields.h5").string() +
                         ": missing; the particle scene has no field bins to compare");
  r.fields = io::FieldFile::read(dir / "fields.h5");
  if (r.fields.snapshots.empty())
    throw io::InputError((dir / "fields.h5").string() + ": holds no snapshot");
  if (fs::exists(dir / "blocks.csv"))
    r.temperature_blocks = compare::read_temperature_blocks(r.fields.grid, dir / "blocks.csv");
  for (int d = 0; d < r.parameters.scene.dim; ++d)
    r.walled[d] = !r.parameters.scene.boundary[d].periodic;
  return r;
}

} // namespace

static const char* kAxis = "xyz";
std::string wall_name(int d, int side) {
  return std::string(1, kAxis[d]) + (side ? "_upper" : "_lower");
}

// The heated direction: the walled direction whose two thermal walls differ in temperature.
int heated_direction(const SceneParameters& s) {
  for (int d = 0; d < s.dim; ++d) {
    const auto& b = s.boundary[d];
    if (!b.periodic && b.thermal[0] && b.thermal[1] && b.temperature[0] != b.temperature[1])
      return d;
  }
  return -1;
}

struct ContinuumTwin {
  std::string name; // "nominal", "calibrated"
  std::string stage;
  io::Json summary;
  compare::BinnedState state;
};

// Figures and report.md/html by compare/report/ (a Python package), with the first python3 that has matplotlib
// (Debian's python3-matplotlib). A missing python is not an error of the run: it says so.
void write_report(const fs::path& dir) {
  std::string quoted = "'";
  for (char ch : fs::absolute(dir).string())
    quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  quoted += "'";
  for (const char* python : {"/usr/bin/python3", "python3"}) {
    const std::string probe = std::string(python) + " -c 'import matplotlib' >/dev/null 2>&1";
    if (std::system(probe.c_str()) != 0) continue;
    const std::string command = std::string(python) + " " + TWINFLOW_REPORT_SCRIPT + " " + quoted;
    if (std::system(command.c_str()) != 0)
      std::cerr << "twinflow: the report failed (" << command << "); the results are complete\n";
    return;
  }
  std::cerr << "twinflow: no python3 with matplotlib: no figures (apt install python3-matplotlib, "
               "then python3 "
            << TWINFLOW_REPORT_SCRIPT << " " << dir.string() << ")\n";
}

double largest_stderr(const io::Json& results, const std::string& wall) {
  double e = io::number(results, {"walls", wall.c_str(), "heat_flux_in_stderr"});
  if (const io::Json* b = io::find(results, {"walls", wall, "heat_flux_in_stderr_blocking"}))
    for (const auto& x : *b) e = std::max(e, x.get<double>());
  return e;
}

// --set options of the calibrated twin: each thermal wall at the temperature the particle fluid
// reaches at it (extrapolated from the bins beyond the wall layer), i.e. the measured
// wall temperature jump taken out of the boundary condition.
std::vector<std::string> calibrated_twin_overrides(const std::string& run_dir,
                                                   const std::vector<std::string>& command) {
  const ParticleRun run = load_particle_run(run_dir, command);
  const compare::BinnedState particle = run.final_state();
  const auto interior =
      compare::interior_bins(run.fields.grid, run.walled, run.parameters.compare.wall_layer);
  std::vector<std::string> overrides;
  // Kapitza walls exist in the Boussinesq twin only: a low-Mach twin is calibrated by its walls'
  // temperatures.
  const bool kapitza = run.parameters.compare.calibration == "kapitza" &&
                       run.parameters.continuum.model == continuum::Model::Boussinesq;
  if (run.parameters.compare.calibration == "kapitza" && !kapitza)
    std::cout << "run: calibrated twin: Kapitza walls need the Boussinesq twin; this one is "
                 "calibrated by its walls' temperatures\n";
  std::ostringstream conductances, errors, positions; // x lower, x upper, y lower, ...
  conductances << std::setprecision(8);
  errors << std::setprecision(4);
  positions << std::setprecision(6);
  const io::Json& walls = run.summary.at("results");
  const SceneParameters& scene = run.parameters.scene;
  // The twin's walls: the scene's, or the particle walls' effective positions (Gibbs depths).
  std::array<double, 6> plane{};
  for (int d = 0; d < scene.dim; ++d)
    for (int side = 0; side < 2; ++side)
      if (run.parameters.compare.effective_walls && !scene.boundary[d].periodic) {
        const double depth =
            io::number(walls, {"walls", wall_name(d, side).c_str(), "effective_position"});
        if (!std::isfinite(depth))
          throw io::InputError(run_dir + "/particle/summary.json: no wall effective_position "
                                         "(a run from before wall_layers.csv); re-run the "
                                         "particle stage (--force) or set Compare/Effective "
                                         "walls = false");
        plane[2 * d + side] = std::max(depth, 0.0);
      }
  for (int d = 0; d < scene.dim; ++d) {
    const auto& b = scene.boundary[d];
    // The particle wall's heat flow spread over the twin's wall, which is shorter where the
    // walls across it moved in.
    double area_ratio = 1; // scene's wall area / twin's
    for (int e = 0; e < scene.dim; ++e)
      if (e != d) area_ratio *= scene.box[e] / (scene.box[e] - plane[2 * e] - plane[2 * e + 1]);
    for (int side = 0; side < 2; ++side) {
      positions << (d + side ? ", " : "") << plane[2 * d + side];
      double h = 0, h_stderr = 0;
      if (!b.periodic && b.thermal[side]) {
        const auto w =
            compare::wall_fluid_temperature(particle, interior, d, side, plane[2 * d + side]);
        // h_K = q / (T_wall - T_fluid at the wall), from the particle wall's measured heat flow
        const std::string name = wall_name(d, side);
        const double q = area_ratio * io::number(walls, {"walls", name.c_str(), "heat_flux_in"});
        const double q_stderr = area_ratio * largest_stderr(walls, name);
        const double jump = b.temperature[side] - w.value;
        if (kapitza && std::isfinite(q) && q * jump > 0) {
          // h_K = q / (T_wall - T_f), or for the inverse law q / (T_wall^2 (1/T_f - 1/T_wall))
          const double Tw = b.temperature[side];
          const bool inverse = run.parameters.continuum.boundary[d].kapitza_inverse;
          const double driving = inverse ? Tw * Tw * (1 / w.value - 1 / Tw) : jump;
          h = q / driving;
          // Its error from q's and T_f's, taken as independent (d driving / d T_f: -T_w^2 / T_f^2
          // or -1).
          const double driving_stderr = (inverse ? Tw * Tw / (w.value * w.value) : 1.0) * w.stderr_;
          h_stderr = std::fabs(h) * std::hypot(q_stderr / q, driving_stderr / driving);
          if (!std::isfinite(h_stderr)) h_stderr = 0;
        } else if (std::isfinite(w.value)) { // no usable jump: the fluid's wall temperature
          std::ostringstream o;
          o << std::setprecision(10) << "Scene/" << kAxis[d] << " boundaries/"
            << (side ? "Upper" : "Lower") << " wall temperature=" << w.value;
          overrides.push_back(o.str());
        }
      }
      conductances << (d + side ? ", " : "") << h;
      errors << (d + side ? ", " : "") << h_stderr;
    }
  }
  if (run.parameters.compare.effective_walls)
    overrides.push_back("Continuum/Wall positions=" + positions.str());
  if (run.parameters.compare.wall_slip &&
      run.parameters.continuum.model == continuum::Model::Boussinesq) {
    // Navier slip from the particle wall's friction per area zeta, acting at its mean depth
    // h_f: eta u'(plane) = zeta u(h_f), u(h_f) ~ u(plane) + u' (h_f - plane), so
    // b = eta / zeta - (h_f - plane) (eta of the nominal twin, at its reference temperature).
    const io::Json nominal = io::read_json(fs::path(run_dir) / "continuum" / "summary.json",
                                           "the nominal twin runs before the calibrated one");
    const double eta =
        io::number(nominal, {"continuum_parameters", "viscosity", "value_at_reference"});
    std::ostringstream slips;
    slips << std::setprecision(6);
    for (int d = 0; d < scene.dim; ++d)
      for (int side = 0; side < 2; ++side) {
        const std::string name = wall_name(d, side);
        double b = 0;
        if (!scene.boundary[d].periodic && scene.boundary[d].no_slip) {
          const double zeta = io::number(walls, {"walls", name.c_str(), "friction_per_area"});
          const double depth = io::number(walls, {"walls", name.c_str(), "friction_depth"});
          if (!(zeta > 0) || !std::isfinite(eta))
            throw io::InputError(run_dir + "/particle/summary.json: no wall friction_per_area "
                                           "(a run from before it); re-run the particle stage "
                                           "(--force) or set Compare/Wall slip = false");
          b = std::max(eta / zeta - (depth - plane[2 * d + side]), 1e-3);
        }
        slips << (d + side ? ", " : "") << b;
      }
    overrides.push_back("Continuum/Slip lengths=" + slips.str());
  }
  if (kapitza) {
    overrides.push_back("Continuum/Kapitza conductances=" + conductances.str());
    overrides.push_back("Continuum/Kapitza conductance errors=" + errors.str());
  }
  return overrides;
}

int compare_stage(const CommandLine& cl) {
  const fs::path run_dir = cl.target;
  if (!fs::is_directory(run_dir))
    throw io::InputError(run_dir.string() + ": not a run directory (twinflow compare RUNDIR, "
                                            "where RUNDIR is the --out of twinflow run)");
  const ParticleRun run = load_particle_run(run_dir, cl.overrides);
  const SceneParameters& scene = run.parameters.scene;
  const io::Grid& grid = run.fields.grid;
  const double wall_layer = run.parameters.compare.wall_layer;

  std::vector<ContinuumTwin> twins;
  for (const auto& [name, stage] : {std::pair<std::string, std::string>{"nominal", "continuum"},
                                    {"calibrated", "continuum_calibrated"}}) {
    const fs::path dir = run_dir / stage;
    if (!fs::exists(dir / "summary.json")) continue;
    ContinuumTwin t;
    t.name = name;
    t.stage = stage;
    t.summary = io::read_json(dir / "summary.json", "");
    t.state = compare::continuum_state(grid, dir / "bins.csv");
    twins.push_back(std::move(t));
  }
  if (twins.empty() || twins.front().name != "nominal")
    throw io::InputError((run_dir / "continuum" / "summary.json").string() +
                         ": missing; the continuum twin has not run (twinflow continuum CASE "
                         "--out " +
                         run_dir.string() + ")");
  const io::StageDirectory stage(run_dir, "compare", true); // derived, cheap: always rewritten
  stage.create();

  const auto interior = compare::interior_bins(grid, run.walled, wall_layer);
  const ContinuumTwin& nominal = twins.front();
  // Scales: the nominal wall temperature difference (else the continuum's temperature range)
  // and the nominal continuum's largest speed.
  const int heated = heated_direction(scene);
  double dT = 0;
  if (heated >= 0) {
    dT = std::fabs(scene.boundary[heated].temperature[0] - scene.boundary[heated].temperature[1]);
  } else {
    double lo = INFINITY, hi = -INFINITY;
    for (double T : nominal.state.temperature) lo = std::min(lo, T), hi = std::max(hi, T);
    dT = hi - lo;
  }
  const double speed_scale =
      io::number(nominal.summary, {"results", "max_speed_chi_over_H"}) *
      io::number(nominal.summary, {"dimensionless", "velocity_scale_chi_over_H"});
  const bool compare_velocity = std::isfinite(speed_scale) && speed_scale > 0;

  io::Json metrics = io::Json::object();
  metrics["stage"] = "compare";
  metrics["case"] = run.parameters.name;
  metrics["provenance"] = io::provenance();
  metrics["wall_layer"] = wall_layer;
  {
    // The thickness actually left out: whole bins, so a layer rounds up to bin edges.
    double excluded = 0;
    for (int d = 0; d < grid.dim; ++d)
      if (run.walled[d])
        excluded =
            std::max(excluded, std::ceil(wall_layer / grid.spacing[d] - 1e-9) * grid.spacing[d]);
    metrics["wall_layer_excluded"] = excluded;
  }
  long n_interior = 0;
  for (char c : interior) n_interior += c;
  metrics["bins"] = io::Json::array();
  for (int d = 0; d < grid.dim; ++d) metrics["bins"].push_back(double(grid.counts[d]));
  metrics["interior_bins"] = double(n_interior);
  metrics["temperature_scale"] = dT;
  metrics["velocity_scale"] = compare_velocity ? speed_scale : std::nan("");
  metrics["density_scale"] = scene.density; // the mean number density
  metrics["temperature_field"] = "T_kinetic (particle) against T (continuum), / temperature_scale";

  const io::Json& presults = run.summary.at("results");
  io::Json table = io::Json::object();
  table["wall_seconds_particle"] = io::number(presults, {"wall_seconds"});
  table["particle_steps"] =
      io::number(presults, {"N"}) *
      (io::number(presults, {"steps"}) + io::number(presults, {"equilibration_steps"}));

  // Particle heat flow through the heated direction's walls, as a Nusselt number against the
  // nominal twin's conduction flux kappa dT / H (the same kappa for every twin).
  io::Json particle = io::Json::object();
  const double q0 = io::number(nominal.summary, {"dimensionless", "conduction_flux"});
  double q_particle = std::nan("");
  if (heated >= 0) {
    const int hot =
        scene.boundary[heated].temperature[0] > scene.boundary[heated].temperature[1] ? 0 : 1;
    const auto flux = [&](int side, const char* key) {
      return io::number(presults, {"walls", wall_name(heated, side).c_str(), key});
    };
    const double q_in = flux(hot, "heat_flux_in"), q_out = -flux(1 - hot, "heat_flux_in");
    const double se =
        std::hypot(flux(hot, "heat_flux_in_stderr"), flux(1 - hot, "heat_flux_in_stderr"));
    // The stated error: each wall's largest over its blockings (1, 2, 4 blocks merged), as for
    // the wall temperatures (a roll slower than a block makes the 20-block error too small).
    const double se_stated = std::hypot(largest_stderr(presults, wall_name(heated, hot)),
                                        largest_stderr(presults, wall_name(heated, 1 - hot)));
    q_particle = 0.5 * (q_in + q_out);
    particle["heat_flux_hot_wall"] = q_in;
    particle["heat_flux_cold_wall"] = q_out;
    particle["heat_flux"] = q_particle;
    particle["heat_flux_stderr"] = 0.5 * se_stated;
    particle["nusselt"] = q_particle / q0;
    particle["nusselt_stderr"] = 0.5 * se_stated / q0;
    particle["nusselt_stderr_20_blocks"] = 0.5 * se / q0;
    // In a steady state the two walls carry the same flow; their difference is the fluid
    // still heating or cooling.
    particle["nusselt_hot_wall"] = q_in / q0;
    particle["nusselt_cold_wall"] = q_out / q0;
    particle["wall_imbalance_over_stderr"] = (q_in - q_out) / se;
    table["nusselt_particle"] = q_particle / q0;
    table["nusselt_particle_stderr"] = 0.5 * se_stated / q0;
  }
  // The fluid's temperature at each thermal wall, and the jump from the wall's own.
  const compare::BinnedState final_state = run.final_state();
  io::Json jumps = io::Json::object();
  for (int d = 0; d < scene.dim; ++d) {
    const auto& b = scene.boundary[d];
    if (b.periodic) continue;
    for (int side = 0; side < 2; ++side) {
      if (!b.thermal[side]) continue;
      const auto w = compare::wall_fluid_temperature(final_state, interior, d, side);
      io::Json j = io::Json::object();
      j["wall_temperature"] = b.temperature[side];
      j["fluid_temperature_at_wall"] = w.value;
      j["fluid_temperature_at_wall_stderr"] = w.stderr_;
      if (!w.blocking.empty()) { // the error with 1, 2, 4 adjacent blocks merged
        j["fluid_temperature_at_wall_stderr_blocking"] = io::Json::array();
        for (double e : w.blocking) j["fluid_temperature_at_wall_stderr_blocking"].push_back(e);
      }
      j["jump"] = b.temperature[side] - w.value;
      j["extrapolated_from_distance"] = w.extrapolated_from;
      const double plane =
          io::number(presults, {"walls", wall_name(d, side).c_str(), "effective_position"});
      if (std::isfinite(plane)) { // the same at the wall's effective position
        j["effective_position"] = plane;
        j["effective_position_stderr"] = io::number(
            presults, {"walls", wall_name(d, side).c_str(), "effective_position_stderr"});
        const auto at = compare::wall_fluid_temperature(final_state, interior, d, side, plane);
        j["fluid_temperature_at_effective_position"] = at.value;
        j["jump_at_effective_position"] = b.temperature[side] - at.value;
      }
      jumps[wall_name(d, side)] = j;
    }
  }
  particle["wall_temperature_jumps"] = jumps;
  particle["wall_seconds"] = io::number(presults, {"wall_seconds"});
  metrics["particle"] = particle;

  io::Json twins_json = io::Json::object();
  std::cout << std::setprecision(4);
  std::cout << "compare: " << n_interior << " interior bins (wall layer " << wall_layer
            << "), temperature scale " << dT;
  if (compare_velocity) std::cout << ", velocity scale " << speed_scale;
  std::cout << "\n";
  if (heated >= 0)
    std::cout << "compare: particle Nu = " << io::number(particle, {"nusselt"}) << " +- "
              << io::number(particle, {"nusselt_stderr"}) << " (hot wall "
              << io::number(particle, {"nusselt_hot_wall"}) << ", cold wall "
              << io::number(particle, {"nusselt_cold_wall"}) << "; with 20 blocks: +- "
              << io::number(particle, {"nusselt_stderr_20_blocks"}) << ")\n";
  for (const ContinuumTwin& t : twins) {
    io::Json j = io::Json::object();
    j["stage"] = t.stage;
    if (t.name == "calibrated") {
      const bool boussinesq = run.parameters.continuum.model == continuum::Model::Boussinesq;
      std::string calibration =
          run.parameters.compare.calibration != "kapitza" || !boussinesq
              ? "walls at the fluid's wall temperatures"
          : run.parameters.continuum.boundary[0].kapitza_inverse
              ? "Kapitza walls, inverse law (h_K T_w^2 (1/T_f - 1/T_w) = the particle wall's "
                "heat flux)"
              : "Kapitza walls (h_K = the particle wall's heat flux / its jump)";
      if (run.parameters.compare.wall_slip && boussinesq)
        calibration += "; Navier slip at no-slip walls (b from the particle wall's friction)";
      if (run.parameters.compare.effective_walls)
        calibration += "; walls at their effective positions (Gibbs depths)";
      j["calibration"] = calibration;
    }
    const auto T = compare::temperature_distance(final_state, t.state, interior, dT);
    j["temperature"] = T.to_json();
    table["temperature_l2_" + t.name] = T.l2;
    table["temperature_l2_" + t.name + "_stderr"] = T.l2_stderr;
    table["temperature_l2_noise"] = T.noise;
    table["temperature_max_" + t.name] = T.max;
    std::cout << "compare: " << t.name << " twin: temperature L2 " << T.l2 << " +- " << T.l2_stderr
              << " (noise " << T.noise << "), max " << T.max << " +- " << T.max_stderr;
    if (compare_velocity) {
      const auto v = compare::velocity_distance(final_state, t.state, interior, speed_scale);
      j["velocity"] = v.to_json();
      table["velocity_l2_" + t.name] = v.l2;
      table["velocity_l2_" + t.name + "_stderr"] = v.l2_stderr;
      table["velocity_l2_noise"] = v.noise;
      std::cout << "; velocity L2 " << v.l2 << " +- " << v.l2_stderr << " (noise " << v.noise
                << ")";
    }
    if (!t.state.density.empty()) { // the low-Mach twin's n(P, T) against the particles'
      const auto n = compare::density_distance(final_state, t.state, interior, scene.density);
      j["density"] = n.to_json();
      table["density_l2_" + t.name] = n.l2;
      table["density_l2_" + t.name + "_stderr"] = n.l2_stderr;
      table["density_l2_noise"] = n.noise;
      std::cout << "; density L2 " << n.l2 << " +- " << n.l2_stderr << " (noise " << n.noise << ")";
    }
    std::cout << "\n";
    const double nu_own = io::number(t.summary, {"results", "nusselt_volume_average"});
    const double q_own = io::number(t.summary, {"dimensionless", "conduction_flux"});
    if (heated >= 0 && std::isfinite(nu_own)) {
      // Its heat flow over the scene's wall area, as the particle's (a twin with its walls
      // moved in has a smaller wall; flux per own area = Nu_own kappa dT / H_own).
      double area_ratio = 1;
      const io::Json* own_box = io::find(t.summary, {"continuum_parameters", "box"});
      if (own_box && own_box->is_array() && own_box->size() == std::size_t(scene.dim))
        for (int e = 0; e < scene.dim; ++e)
          if (e != heated) area_ratio *= (*own_box)[e].get<double>() / scene.box[e];
      if (io::find(t.summary, {"continuum_parameters", "scene_box"}))
        j["wall_area_over_scene"] = area_ratio;
      const double q = nu_own * q_own * area_ratio;
      j["nusselt_own"] = nu_own; // against this twin's own wall temperature difference
      j["heat_flux"] = q;
      j["nusselt"] = q / q0; // against the nominal conduction flux, as the particle's
      j["nusselt_particle_minus_twin"] = q_particle / q0 - q / q0;
      j["nusselt_relative_difference"] = q_particle / q - 1;
      table["nusselt_" + t.name] = q / q0;
      // The twin's own error: its heat flux's response to the measured coefficients' errors
      // (and, calibrated, to its Kapitza conductances').
      const double rel =
          io::number(t.summary, {"coefficient_uncertainty", "heat_flux_relative_stderr"});
      j["nusselt_stderr_from_coefficients"] = rel * q / q0;
      table["nusselt_" + t.name + "_stderr"] = rel * q / q0;
      std::cout << "compare: " << t.name << " twin: Nu = " << q / q0;
      if (std::isfinite(rel))
        std::cout << " +- " << rel * q / q0
                  << (t.name == "calibrated" && run.parameters.compare.calibration == "kapitza"
                          ? " (coefficients' and h_K's errors)"
                          : " (coefficients' errors)");
      std::cout << " (own dT: " << nu_own
                << "); particle / twin heat flux - 1 = " << q_particle / q - 1 << "\n";
    }
    j["rayleigh"] = io::number(t.summary, {"dimensionless", "rayleigh"});
    table["rayleigh_" + t.name] = io::number(t.summary, {"dimensionless", "rayleigh"});
    table["wall_seconds_continuum" + std::string(t.name == "nominal" ? "" : "_" + t.name)] =
        io::number(t.summary, {"stage_wall_time_s"});
    twins_json[t.name] = j;
  }
  table["rayleigh"] = io::number(nominal.summary, {"dimensionless", "rayleigh"});
  table["prandtl"] = io::number(nominal.summary, {"dimensionless", "prandtl"});
  metrics["twins"] = twins_json;

  // Error against run time: the same distances for each cumulative snapshot of the run.
  std::ostringstream series;
  series << std::setprecision(8);
  series << "# distance of each cumulative particle snapshot to the twins (interior bins), "
            "units of the temperature / velocity scale of metrics.json\n";
  series << "snapshot,time,wall_seconds,particle_steps";
  for (const auto& t : twins) {
    series << ",temperature_l2_" << t.name << ",temperature_l2_" << t.name << "_stderr";
    if (compare_velocity)
      series << ",velocity_l2_" << t.name << ",velocity_l2_" << t.name << "_stderr";
  }
  series << ",temperature_noise" << (compare_velocity ? ",velocity_noise" : "") << "\n";
  for (std::size_t s = 0; s < run.fields.snapshots.size(); ++s) {
    const auto& snap = run.fields.snapshots[s];
    const compare::BinnedState p = compare::particle_state(grid, snap);
    series << s << "," << snap.time << "," << snap.wall_seconds << "," << snap.particle_steps;
    double t_noise = 0, v_noise = 0;
    for (const auto& t : twins) {
      const auto T = compare::temperature_distance(p, t.state, interior, dT);
      series << "," << T.l2 << "," << T.l2_stderr;
      t_noise = T.noise;
      if (compare_velocity) {
        const auto v = compare::velocity_distance(p, t.state, interior, speed_scale);
        series << "," << v.l2 << "," << v.l2_stderr;
        v_noise = v.noise;
      }
    }
    series << "," << t_noise;
    if (compare_velocity) series << "," << v_noise;
    series << "\n";
  }

  std::vector<std::pair<std::string, const compare::BinnedState*>> continua;
  for (const auto& t : twins) continua.emplace_back(t.name, &t.state);
  metrics["table_row"] = table;
  metrics["files"] = io::Json::array();
  for (const char* f : {"bins.csv", "profiles.csv", "error_vs_time.csv"})
    metrics["files"].push_back(f);
  io::write_file_atomically(stage.file("bins.csv"),
                            compare::bins_csv(final_state, interior, continua));
  io::write_file_atomically(stage.file("profiles.csv"),
                            compare::midline_profiles_csv(final_state, continua));
  io::write_file_atomically(stage.file("error_vs_time.csv"), series.str());
  io::write_file_atomically(stage.file("metrics.json"), io::dump(metrics)); // last: complete
  std::cout << "compare: results in " << stage.path().string()
            << " (metrics.json, bins.csv, profiles.csv, error_vs_time.csv)" << std::endl;
  write_report(run_dir);
  return 0;
}

} // namespace twinflow::app
