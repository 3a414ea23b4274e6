#include "compare/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "io/files.hpp"
#include "particle/wall_summary.hpp"

namespace twinflow::compare {

namespace fs = std::filesystem;

namespace {
// A number for a person: 4 significant digits; "n/a" where there is none.
std::string say(double value, int digits = 4) {
  if (!std::isfinite(value)) return "n/a";
  std::ostringstream s;
  s << std::setprecision(digits) << value;
  return s.str();
}

// What one twin's verdict line says, and whether it agrees with the particles.
struct TwinVerdict {
  std::string line;
  bool agrees = true;
  std::vector<std::string> disagreements;
};

// A difference counts as within noise when the L2 exceeds the noise by at most this many of its
// standard errors; Nu agrees when |particle - twin| is at most this many combined standard
// errors (the report's rule, compare/report/run.py WITHIN_NOISE_STDERRS).
constexpr double kWithinStderrs = 2;

// Within errors: L2 no larger than what the particle's noise and the twin's inputs' errors give
// together, or above it by at most kWithinStderrs of L2's own error.
void distance_verdict(TwinVerdict& v, const char* name, const Distance& d) {
  const double errors = std::hypot(d.noise, d.noise_twin);
  const bool within =
      std::isfinite(d.l2) && std::isfinite(errors) &&
      (d.l2 <= errors || (d.l2_stderr > 0 && d.l2 - errors <= kWithinStderrs * d.l2_stderr));
  v.line += std::string("; ") + name + " L2 " + say(d.l2, 3) + " +- " + say(d.l2_stderr, 2) +
            " against noise " + say(d.noise, 3) +
            (d.noise_twin > 0 ? " and the twin's inputs' " + say(d.noise_twin, 3) : "") + ": " +
            (within ? "within errors" : "NOT within errors");
  if (!within) v.agrees = false, v.disagreements.push_back(name);
}
} // namespace

BinnedState ParticleRecord::final_state() const {
  BinnedState s = particle_state(fields.grid, fields.snapshots.back());
  s.temperature_blocks = temperature_blocks;
  return s;
}

ParticleRecord read_particle_record(const fs::path& run_dir, const scene::SceneParameters& scene) {
  ParticleRecord r;
  const fs::path dir = run_dir / "particle";
  r.summary = io::read_json(dir / "summary.json",
                            "the particle stage has not finished in " + run_dir.string() +
                                " (twinflow run CASE --out " + run_dir.string() + ")");
  if (!fs::exists(dir / "fields.h5"))
    throw io::InputError((dir / "fields.h5").string() +
                         ": missing; the particle scene has no field bins to compare");
  r.fields = io::FieldFile::read(dir / "fields.h5");
  if (r.fields.snapshots.empty())
    throw io::InputError((dir / "fields.h5").string() + ": holds no snapshot");
  if (fs::exists(dir / "blocks.csv"))
    r.temperature_blocks = read_temperature_blocks(r.fields.grid, dir / "blocks.csv");
  for (int d = 0; d < scene.dim; ++d) r.walled[d] = !scene.boundary[d].periodic;
  return r;
}

std::vector<TwinRecord> read_twins(const fs::path& run_dir, const io::Grid& grid) {
  std::vector<TwinRecord> twins;
  for (const auto& [name, stage] : {std::pair<std::string, std::string>{"nominal", "continuum"},
                                    {"calibrated", "continuum_calibrated"}}) {
    const fs::path dir = run_dir / stage;
    if (!fs::exists(dir / "summary.json")) continue;
    TwinRecord t;
    t.name = name;
    t.stage = stage;
    t.summary = io::read_json(dir / "summary.json");
    t.state = continuum_state(grid, dir / "bins.csv");
    // Only a responses file the twin's own summary names (an older one may lie beside it).
    const io::Json* files = io::find(t.summary, {"files"});
    const bool has_responses =
        files && files->is_array() &&
        std::find(files->begin(), files->end(), "coefficient_responses.csv") != files->end();
    if (has_responses) read_coefficient_responses(dir / "coefficient_responses.csv", t.state);
    twins.push_back(std::move(t));
  }
  if (twins.empty() || twins.front().name != "nominal")
    throw io::InputError((run_dir / "continuum" / "summary.json").string() +
                         ": missing; the continuum twin has not run (twinflow continuum CASE "
                         "--out " +
                         run_dir.string() + ")");
  return twins;
}

namespace {
// The scales distances are shown in: the nominal wall temperature difference (else the
// continuum's temperature range) and the nominal continuum's largest speed, at least 1% of its
// diffusive speed chi / H (a twin at rest, e.g. heated from above, has only its
// discretisation's spurious flow, ~1e-6 chi / H). They set the numbers shown, not the verdicts:
// distances are judged against the noise in the same scale.
struct Scales {
  int heated = -1;
  double temperature = 0, speed = 0;
  bool velocity = false;
};
Scales comparison_scales(const scene::SceneParameters& scene, const TwinRecord& nominal) {
  Scales s;
  s.heated = scene.heated_direction();
  if (s.heated >= 0) {
    const auto& b = scene.boundary[s.heated];
    s.temperature = std::fabs(b.temperature[0] - b.temperature[1]);
  } else {
    double lo = INFINITY, hi = -INFINITY;
    for (double T : nominal.state.temperature) lo = std::min(lo, T), hi = std::max(hi, T);
    s.temperature = hi - lo;
  }
  const double diffusive_speed =
      io::number(nominal.summary, {"dimensionless", "velocity_scale_chi_over_H"});
  s.speed = std::max(io::number(nominal.summary, {"results", "max_speed_chi_over_H"}), 0.01) *
            diffusive_speed;
  s.velocity = std::isfinite(s.speed) && s.speed > 0;
  return s;
}

// The bins compared and the scales, at the head of metrics.json.
void describe_comparison(io::Json& metrics, const io::Grid& grid, const ParticleRecord& run,
                         const std::vector<char>& interior, double wall_layer, const Scales& s,
                         const scene::SceneParameters& scene) {
  metrics["wall_layer"] = wall_layer;
  double excluded = 0; // the thickness actually left out: whole bins, rounded up to bin edges
  for (int d = 0; d < grid.dim; ++d)
    if (run.walled[d])
      excluded =
          std::max(excluded, std::ceil(wall_layer / grid.spacing[d] - 1e-9) * grid.spacing[d]);
  metrics["wall_layer_excluded"] = excluded;
  long n_interior = 0;
  for (char c : interior) n_interior += c;
  metrics["bins"] = io::Json::array();
  for (int d = 0; d < grid.dim; ++d) metrics["bins"].push_back(double(grid.counts[d]));
  metrics["interior_bins"] = double(n_interior);
  metrics["temperature_scale"] = s.temperature;
  metrics["velocity_scale"] = s.velocity ? s.speed : std::nan("");
  metrics["density_scale"] = scene.density; // the mean number density
  metrics["temperature_field"] = "T_kinetic (particle) against T (continuum), / temperature_scale";
}

// The relative error of the conduction flux q0 = kappa dT / H from the nominal twin's measured
// kappa amplitude (q0 is proportional to it: the Kirchhoff integral of continuum/parameters.cpp);
// NaN when the twin's coefficients carry no measured errors. kappa's exponent moves q0 by ~0.4%
// per its stderr (0.1) at dT / T = 1, against the amplitude's ~1.7%: left out.
double conduction_flux_relative_stderr(const io::Json& nominal_summary) {
  const io::Json* k = io::find(nominal_summary, {"coefficient_uncertainty", "conductivity"});
  if (!k) return std::nan("");
  return io::number(*k, {"stderr"}) / io::number(*k, {"value"});
}

// The particle's heat flow through the heated direction's walls as a Nusselt number against
// the nominal twin's conduction flux q0 = kappa dT / H (the same q0 for every twin). Two errors:
// the heat flow's alone (what the gap to a twin carries, whose Nu has the same q0), and with q0's
// kappa error (what the particle Nu read alone carries: each transport stage has its own kappa).
io::Json particle_heat_flow(const io::Json& presults, const scene::SceneParameters& scene,
                            int heated, double q0, double q0_relative_stderr) {
  io::Json particle = io::Json::object();
  if (heated < 0) return particle;
  // Magnitudes: the particle's flux is counted from its hot wall to its cold one.
  const int hot =
      scene.boundary[heated].temperature[0] > scene.boundary[heated].temperature[1] ? 0 : 1;
  const auto flux = [&](int side, const char* key) {
    return io::number(presults, {"walls", scene::wall_name(heated, side).c_str(), key});
  };
  const double q_in = flux(hot, "heat_flux_in"), q_out = -flux(1 - hot, "heat_flux_in");
  const double se =
      std::hypot(flux(hot, "heat_flux_in_stderr"), flux(1 - hot, "heat_flux_in_stderr"));
  // The stated error: the largest over the blockings (1, 2, 4 blocks merged) of the one series
  // across the pair, as for the wall temperatures (a roll slower than a block makes the
  // 20-block error too small).
  const double se_stated = particle::wall_pair_heat_flux(presults, heated).stderr_;
  const double q = 0.5 * (q_in + q_out);
  particle["heat_flux_hot_wall"] = q_in;
  particle["heat_flux_cold_wall"] = q_out;
  particle["heat_flux"] = q;
  particle["heat_flux_stderr"] = se_stated;
  particle["nusselt"] = q / q0;
  particle["nusselt_stderr"] = se_stated / q0;
  particle["nusselt_stderr_20_blocks"] = 0.5 * se / q0;
  if (std::isfinite(q0_relative_stderr)) {
    const double se_conductivity = q0_relative_stderr * q / q0;
    particle["nusselt_stderr_conductivity"] = se_conductivity;
    particle["nusselt_stderr_with_conductivity"] = std::hypot(se_stated / q0, se_conductivity);
  }
  // In a steady state the two walls carry the same flow; their difference is the fluid still
  // heating or cooling.
  particle["nusselt_hot_wall"] = q_in / q0;
  particle["nusselt_cold_wall"] = q_out / q0;
  particle["wall_imbalance_over_stderr"] = (q_in - q_out) / se;
  return particle;
}

// The fluid's temperature at each thermal wall, and the jump from the wall's own.
io::Json wall_temperature_jumps(const BinnedState& final_state, const std::vector<char>& interior,
                                const scene::SceneParameters& scene, const io::Json& presults) {
  io::Json jumps = io::Json::object();
  for (int d = 0; d < scene.dim; ++d) {
    const auto& b = scene.boundary[d];
    if (b.periodic) continue;
    for (int side = 0; side < 2; ++side) {
      if (!b.thermal[side]) continue;
      const auto w = wall_fluid_temperature(final_state, interior, d, side);
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
      const std::string name = scene::wall_name(d, side);
      const double plane = io::number(presults, {"walls", name.c_str(), "effective_position"});
      if (std::isfinite(plane)) { // the same at the wall's effective position
        j["effective_position"] = plane;
        j["effective_position_stderr"] =
            io::number(presults, {"walls", name.c_str(), "effective_position_stderr"});
        const auto at = wall_fluid_temperature(final_state, interior, d, side, plane);
        j["fluid_temperature_at_effective_position"] = at.value;
        j["jump_at_effective_position"] = b.temperature[side] - at.value;
      }
      jumps[name] = j;
    }
  }
  return jumps;
}

// One twin's field distances (temperature, velocity, density), into its JSON, the table row,
// its verdict and the log.
void field_distances(const TwinRecord& t, const BinnedState& final_state,
                     const std::vector<char>& interior, const Scales& s, double density_scale,
                     io::Json& j, io::Json& table, TwinVerdict& verdict, std::ostream& log) {
  const auto T = temperature_distance(final_state, t.state, interior, s.temperature);
  j["temperature"] = T.to_json();
  table["temperature_l2_" + t.name] = T.l2;
  table["temperature_l2_" + t.name + "_stderr"] = T.l2_stderr;
  table["temperature_l2_noise"] = T.noise;
  table["temperature_max_" + t.name] = T.max;
  distance_verdict(verdict, "temperature", T);
  log << "compare: " << t.name << " twin: temperature L2 " << T.l2 << " +- " << T.l2_stderr
      << " (noise " << T.noise << "), max " << T.max << " +- " << T.max_stderr;
  if (s.velocity) {
    const auto v = velocity_distance(final_state, t.state, interior, s.speed);
    j["velocity"] = v.to_json();
    table["velocity_l2_" + t.name] = v.l2;
    table["velocity_l2_" + t.name + "_stderr"] = v.l2_stderr;
    table["velocity_l2_noise"] = v.noise;
    distance_verdict(verdict, "velocity", v);
    log << "; velocity L2 " << v.l2 << " +- " << v.l2_stderr << " (noise " << v.noise << ")";
  }
  if (!t.state.density.empty()) { // the low-Mach and compressible twins' n against the particles'
    const auto n = density_distance(final_state, t.state, interior, density_scale);
    j["density"] = n.to_json();
    table["density_l2_" + t.name] = n.l2;
    table["density_l2_" + t.name + "_stderr"] = n.l2_stderr;
    table["density_l2_noise"] = n.noise;
    log << "; density L2 " << n.l2 << " +- " << n.l2_stderr << " (noise " << n.noise << ")";
  }
  log << "\n";
}

// One twin's heat flow over the scene's wall area as a Nusselt number against q0 (a twin with
// its walls moved in has a smaller wall: flux per own area = Nu_own kappa dT / H_own), its own
// error from its coefficients', and the Nu part of its verdict.
void twin_heat_flow(const TwinRecord& t, const scene::SceneParameters& scene,
                    const io::Json& particle, double q0, const CompareParameters& compare,
                    io::Json& j, io::Json& table, TwinVerdict& verdict, std::ostream& log) {
  const double nu_own = io::number(t.summary, {"results", "nusselt_volume_average"});
  const double q_own = std::abs(io::number(t.summary, {"dimensionless", "conduction_flux"}));
  const int heated = scene.heated_direction();
  if (heated < 0 || !std::isfinite(nu_own)) return;
  double area_ratio = 1;
  const io::Json* own_box = io::find(t.summary, {"continuum_parameters", "box"});
  if (own_box && own_box->is_array() && own_box->size() == std::size_t(scene.dim))
    for (int e = 0; e < scene.dim; ++e)
      if (e != heated) area_ratio *= (*own_box)[e].get<double>() / scene.box[e];
  if (io::find(t.summary, {"continuum_parameters", "scene_box"}))
    j["wall_area_over_scene"] = area_ratio;
  const double q = nu_own * q_own * area_ratio, q_particle = io::number(particle, {"heat_flux"});
  j["nusselt_own"] = nu_own; // against this twin's own wall temperature difference
  j["heat_flux"] = q;
  j["nusselt"] = q / q0; // against the nominal conduction flux, as the particle's
  j["nusselt_particle_minus_twin"] = q_particle / q0 - q / q0;
  j["nusselt_relative_difference"] = q_particle / q - 1;
  table["nusselt_" + t.name] = q / q0;
  // The twin's own error: its heat flux's response to the measured coefficients' errors (and,
  // calibrated, to its Kapitza conductances').
  const double rel =
      io::number(t.summary, {"coefficient_uncertainty", "heat_flux_relative_stderr"});
  const double se_t = rel * q / q0;
  j["nusselt_stderr_from_coefficients"] = se_t;
  table["nusselt_" + t.name + "_stderr"] = se_t;
  log << "compare: " << t.name << " twin: Nu = " << q / q0;
  if (std::isfinite(rel))
    log << " +- " << se_t
        << (t.name == "calibrated" && compare.calibration == "kapitza"
                ? " (coefficients' and h_K's errors)"
                : " (coefficients' errors)");
  log << " (own dT: " << nu_own << "); particle / twin heat flux - 1 = " << q_particle / q - 1
      << "\n";
  const double nu_p = io::number(particle, {"nusselt"});
  const double se_p = io::number(particle, {"nusselt_stderr"});
  const double combined = std::hypot(se_p, std::isfinite(se_t) ? se_t : 0.0);
  const double over = std::fabs(nu_p - q / q0) / combined;
  const bool within = std::isfinite(over) && over <= kWithinStderrs;
  std::ostringstream nu;
  nu << "Nu " << say(nu_p) << " +- " << say(se_p, 2) << " (particle) against " << say(q / q0)
     << " +- " << (std::isfinite(se_t) ? say(se_t, 2) : "n/a (no measured coefficients)")
     << " (twin), " << std::showpos << std::fixed << std::setprecision(1)
     << 100 * (q_particle / q - 1) << std::noshowpos << "%, " << say(over, 2)
     << " combined errors: " << (within ? "within errors" : "NOT within errors");
  verdict.line = nu.str() + verdict.line;
  if (!within)
    verdict.agrees = false, verdict.disagreements.insert(verdict.disagreements.begin(), "Nu");
}

// The prediction tolerances (issue 44, fixed before the prediction suite ran; docs/validation.md,
// "The prediction suite"): Nu within 2 combined errors + 2% of the twin's; temperature L2 within
// 1.5x its noise or 1% of dT; velocity L2 within 1.5x its noise; density L2 within 2x its noise.
// Beside compare's strict verdict, which stays as it is. Each distance also carries its
// systematic part, sqrt(L2^2 - noise^2), with its error.
io::Json prediction_block(const io::Json& twin, const io::Json& particle) {
  io::Json p = io::Json::object();
  p["rule"] = "Nu: |particle - twin| <= 2 combined errors + 2% of the twin's; temperature L2 <= "
              "1.5 noise or <= 0.01 (units of dT); velocity L2 <= 1.5 noise; density L2 <= 2 noise";
  bool all = true;
  const auto tolerance = [&](const char* name, bool pass, io::Json detail) {
    detail["pass"] = pass;
    p[name] = detail;
    all = all && pass;
  };
  if (const io::Json* nu = io::find(twin, {"nusselt"})) {
    const double nu_t = nu->get<double>(), nu_p = io::number(particle, {"nusselt"});
    const double se_t = io::number(twin, {"nusselt_stderr_from_coefficients"});
    const double combined =
        std::hypot(io::number(particle, {"nusselt_stderr"}), std::isfinite(se_t) ? se_t : 0.0);
    const double allowed = 2 * combined + 0.02 * nu_t;
    tolerance("nusselt", std::fabs(nu_p - nu_t) <= allowed,
              {{"particle", nu_p},
               {"twin", nu_t},
               {"gap", nu_p / nu_t - 1},
               {"allowed", allowed},
               {"combined_stderr", combined}});
  }
  const auto distance = [&](const char* name, double noise_factor, double absolute) {
    const io::Json* d = io::find(twin, {name});
    if (!d) return;
    const double l2 = io::number(*d, {"l2"}), noise = io::number(*d, {"noise"});
    const double l2_se = io::number(*d, {"l2_stderr"});
    const double excess = std::sqrt(std::max(0.0, l2 * l2 - noise * noise));
    // d(excess) = l2 d(l2) / excess; at excess 0 the bound that l2's error allows
    const double excess_se = excess > 0 ? l2 * l2_se / excess : std::sqrt(2 * l2 * l2_se);
    const bool pass = l2 <= noise_factor * noise || l2 <= absolute;
    tolerance(name, pass,
              {{"l2", l2},
               {"noise", noise},
               {"over_noise", l2 / noise},
               {"allowed_over_noise", noise_factor},
               {"systematic", excess},
               {"systematic_stderr", excess_se}});
  };
  distance("temperature", 1.5, 0.01);
  distance("velocity", 1.5, 0.0);
  distance("density", 2.0, 0.0);
  p["pass"] = all;
  return p;
}

// The verdict, first in the report and last on the console: one headline, one line per twin.
io::Json verdict_lines(const std::vector<std::pair<std::string, TwinVerdict>>& verdicts) {
  std::string headline = "verdict:";
  for (std::size_t i = 0; i < verdicts.size(); ++i) {
    const auto& [name, v] = verdicts[i];
    std::string which;
    for (std::size_t k = 0; k < v.disagreements.size(); ++k)
      which += (k ? ", " : "") + v.disagreements[k];
    headline += std::string(i ? ";" : "") + " the " + name + " twin " +
                (v.agrees ? "matches the particles within errors"
                          : "differs from the particles beyond errors (" + which + ")");
  }
  io::Json lines = io::Json::array();
  lines.push_back(headline);
  for (const auto& [name, v] : verdicts) lines.push_back(v.line);
  return lines;
}

// Error against run time: the same distances for each cumulative snapshot of the run.
std::string error_vs_time(const ParticleRecord& run, const std::vector<TwinRecord>& twins,
                          const std::vector<char>& interior, const Scales& s) {
  std::ostringstream series;
  series << std::setprecision(8);
  series << "# distance of each cumulative particle snapshot to the twins (interior bins), "
            "units of the temperature / velocity scale of metrics.json\n";
  series << "snapshot,time,wall_seconds,particle_steps";
  for (const auto& t : twins) {
    series << ",temperature_l2_" << t.name << ",temperature_l2_" << t.name << "_stderr";
    if (s.velocity) series << ",velocity_l2_" << t.name << ",velocity_l2_" << t.name << "_stderr";
  }
  series << ",temperature_noise" << (s.velocity ? ",velocity_noise" : "") << "\n";
  for (std::size_t k = 0; k < run.fields.snapshots.size(); ++k) {
    const auto& snap = run.fields.snapshots[k];
    const BinnedState p = particle_state(run.fields.grid, snap);
    series << k << "," << snap.time << "," << snap.wall_seconds << "," << snap.particle_steps;
    double t_noise = 0, v_noise = 0;
    for (const auto& t : twins) {
      const auto T = temperature_distance(p, t.state, interior, s.temperature);
      series << "," << T.l2 << "," << T.l2_stderr;
      t_noise = T.noise;
      if (s.velocity) {
        const auto v = velocity_distance(p, t.state, interior, s.speed);
        series << "," << v.l2 << "," << v.l2_stderr;
        v_noise = v.noise;
      }
    }
    series << "," << t_noise;
    if (s.velocity) series << "," << v_noise;
    series << "\n";
  }
  return series.str();
}

// The particles' heat flow and wall jumps; their cost and Nu in the table.
io::Json particle_results(const ParticleRecord& run, const BinnedState& final_state,
                          const std::vector<char>& interior, const scene::SceneParameters& scene,
                          const Scales& scales, double q0, double q0_relative_stderr,
                          io::Json& table) {
  const io::Json& presults = run.summary.at("results");
  table["wall_seconds_particle"] = io::number(presults, {"wall_seconds"});
  table["particle_steps"] =
      io::number(presults, {"N"}) *
      (io::number(presults, {"steps"}) + io::number(presults, {"equilibration_steps"}));
  io::Json particle = particle_heat_flow(presults, scene, scales.heated, q0, q0_relative_stderr);
  if (scales.heated >= 0) {
    table["nusselt_particle"] = particle["nusselt"];
    table["nusselt_particle_stderr"] = particle["nusselt_stderr"];
    if (particle.contains("nusselt_stderr_with_conductivity"))
      table["nusselt_particle_stderr_with_conductivity"] =
          particle["nusselt_stderr_with_conductivity"];
  }
  particle["wall_temperature_jumps"] =
      wall_temperature_jumps(final_state, interior, scene, presults);
  particle["wall_seconds"] = io::number(presults, {"wall_seconds"});
  return particle;
}

void log_particles(std::ostream& log, const io::Json& particle, const std::vector<char>& interior,
                   double wall_layer, const Scales& scales) {
  long n_interior = 0;
  for (char c : interior) n_interior += c;
  log << std::setprecision(4);
  log << "compare: " << n_interior << " interior bins (wall layer " << wall_layer
      << "), temperature scale " << scales.temperature;
  if (scales.velocity) log << ", velocity scale " << scales.speed;
  log << "\n";
  if (scales.heated < 0) return;
  log << "compare: particle Nu = " << io::number(particle, {"nusselt"}) << " +- "
      << io::number(particle, {"nusselt_stderr"}) << " (heat flow";
  if (particle.contains("nusselt_stderr_conductivity"))
    log << "; +- " << io::number(particle, {"nusselt_stderr_conductivity"})
        << " from the twin's kappa in q0";
  log << "; hot wall " << io::number(particle, {"nusselt_hot_wall"}) << ", cold wall "
      << io::number(particle, {"nusselt_cold_wall"}) << "; with 20 blocks: +- "
      << io::number(particle, {"nusselt_stderr_20_blocks"}) << ")\n";
}

// One twin against the particles: its distances, heat flow and verdict; its columns in the table.
io::Json twin_results(const TwinRecord& t, const BinnedState& final_state,
                      const std::vector<char>& interior, const Scales& scales,
                      const scene::SceneParameters& scene, const io::Json& particle, double q0,
                      const CompareParameters& compare, const TwinFacts& twin, io::Json& table,
                      TwinVerdict& verdict, std::ostream& log) {
  io::Json j = io::Json::object();
  j["stage"] = t.stage;
  if (t.name == "calibrated") j["calibration"] = calibration_description(compare, twin);
  field_distances(t, final_state, interior, scales, scene.density, j, table, verdict, log);
  twin_heat_flow(t, scene, particle, q0, compare, j, table, verdict, log);
  if (verdict.line.rfind("; ", 0) == 0) verdict.line.erase(0, 2);
  verdict.line = "particle vs " + t.name + " twin: " + verdict.line;
  j["within_errors"] = verdict.agrees;        // the strict verdict, as a sweep's table reads it
  j["beyond_errors"] = verdict.disagreements; // what it names: "Nu", "temperature", ...
  table["within_errors_" + t.name] = verdict.agrees;
  j["rayleigh"] = io::number(t.summary, {"dimensionless", "rayleigh"});
  table["rayleigh_" + t.name] = io::number(t.summary, {"dimensionless", "rayleigh"});
  table["wall_seconds_continuum" + std::string(t.name == "nominal" ? "" : "_" + t.name)] =
      io::number(t.summary, {"stage_wall_time_s"});
  return j;
}
} // namespace

Comparison compare_twins(const ParticleRecord& run, const std::vector<TwinRecord>& twins,
                         const scene::SceneParameters& scene, const CompareParameters& compare,
                         const TwinFacts& twin, const std::string& case_name) {
  Comparison out;
  const io::Grid& grid = run.fields.grid;
  const auto interior = interior_bins(grid, run.walled, compare.wall_layer);
  const TwinRecord& nominal = twins.front();
  const Scales scales = comparison_scales(scene, nominal);
  io::Json& metrics = out.metrics;
  metrics = io::Json::object();
  metrics["stage"] = "compare";
  metrics["case"] = case_name;
  metrics["provenance"] = io::provenance();
  describe_comparison(metrics, grid, run, interior, compare.wall_layer, scales, scene);

  io::Json table = io::Json::object();
  const double q0 = std::abs(io::number(nominal.summary, {"dimensionless", "conduction_flux"}));
  const BinnedState final_state = run.final_state();
  const io::Json particle =
      particle_results(run, final_state, interior, scene, scales, q0,
                       conduction_flux_relative_stderr(nominal.summary), table);
  metrics["particle"] = particle;
  log_particles(out.log, particle, interior, compare.wall_layer, scales);

  io::Json twins_json = io::Json::object();
  std::vector<std::pair<std::string, TwinVerdict>> verdicts;
  for (const TwinRecord& t : twins) {
    TwinVerdict verdict;
    twins_json[t.name] = twin_results(t, final_state, interior, scales, scene, particle, q0,
                                      compare, twin, table, verdict, out.log);
    verdicts.emplace_back(t.name, verdict);
  }
  table["rayleigh"] = io::number(nominal.summary, {"dimensionless", "rayleigh"});
  table["prandtl"] = io::number(nominal.summary, {"dimensionless", "prandtl"});
  metrics["twins"] = twins_json;
  metrics["verdict"] = verdict_lines(verdicts);
  metrics["prediction"] = prediction_block(twins_json["nominal"], particle);
  table["prediction_pass"] = metrics["prediction"]["pass"];
  out.error_vs_time_csv = error_vs_time(run, twins, interior, scales);

  std::vector<std::pair<std::string, const BinnedState*>> continua;
  for (const auto& t : twins) continua.emplace_back(t.name, &t.state);
  metrics["table_row"] = table;
  metrics["files"] = io::Json::array();
  for (const char* f : {"bins.csv", "profiles.csv", "error_vs_time.csv"})
    metrics["files"].push_back(f);
  out.bins_csv = bins_csv(final_state, interior, continua);
  out.profiles_csv = midline_profiles_csv(final_state, continua);
  return out;
}

} // namespace twinflow::compare
