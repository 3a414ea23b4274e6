// twinflow stability CASE --vary 'Section/Key=V1,V2': the particle stage at every point of the
// grid, in child processes, each classified in one word beside the stability limits that theory
// predicts for it.

#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <set>
#include <sstream>

#include "io/files.hpp"
#include "particle/theory.hpp"
#include "study/grid.hpp"
#include "study/sweeps.hpp"

namespace twinflow::study {

namespace fs = std::filesystem;

namespace {

// The temperature a stable run should hold: the mean of the thermal walls' temperatures, or
// the scene's temperature when no wall exchanges heat. (After a run, a closed ideal fluid's own
// energy equation of state refines the latter: see run_target_temperature.)
double target_temperature(const scene::SceneParameters& scene) {
  const double walls = scene.thermal_wall_mean();
  return walls > 0 ? walls : scene.temperature;
}

// The range of the thermal walls' temperatures ({0, 0} without any).
std::array<double, 2> thermal_wall_range(const scene::SceneParameters& scene) {
  std::array<double, 2> range{{0, 0}};
  bool first = true;
  for (int d = 0; d < scene.dim; ++d)
    if (!scene.boundary[d].periodic)
      for (int side = 0; side < 2; ++side)
        if (scene.boundary[d].thermal[side]) {
          const double T = scene.boundary[d].temperature[side];
          range = first ? std::array<double, 2>{{T, T}}
                        : std::array<double, 2>{{std::min(range[0], T), std::max(range[1], T)}};
          first = false;
        }
  return range;
}

// A closed ideal DPDE fluid started at T with Maxwell velocities holds more energy than its
// equilibrium at T and settles at E / (N (d/2 + c_v + 1)) (docs/case-files.md, "A start-up
// convention": 8% below T at c_v = 10); the particle summary states it, and it is the target.
double run_target_temperature(const scene::SceneParameters& scene, const io::Json& summary) {
  const bool thermal_walls = scene.thermal_wall_mean() > 0;
  const double before_run = target_temperature(scene);
  // 000:(3.21) E/N = (d/2) k T + (c_v + k) T, evaluated by the particle run
  const double energy_equation_of_state =
      io::number(summary, {"results", "T_energy_equation_of_state"});
  return !thermal_walls && std::isfinite(energy_equation_of_state) ? energy_equation_of_state
                                                                   : before_run;
}

// How far T lies outside [low, high], relative to the nearer end (0 inside).
double relative_distance_outside(double T, const std::array<double, 2>& range) {
  return T < range[0] ? 1 - T / range[0] : T > range[1] ? T / range[1] - 1 : 0;
}

struct Prediction {
  double dt_critical, fluctuation_number;
  bool stable;
};

// particle/theory.hpp's limits at the target temperature. constant-sigma friction enters 001's
// isothermal analysis with the fluctuation-dissipation gamma at that temperature.
Prediction predict(const CaseParameters& c) {
  particle::ParticleParameters p = c.particle;
  const double T = target_temperature(c.scene);
  p.temperature = T;
  const bool has_energy = p.energy == particle::EnergyModel::Dpde;
  if (has_energy && p.friction == particle::Friction::ConstantSigma)
    p.gamma = p.sigma * p.sigma / (2 * T); // 000:(2.37): sigma^2 = 2 k Theta gamma, Theta = T
  Prediction out;
  out.dt_critical = particle::marsh_yeomans_critical_dt(p); // 001:(28)
  // 000:(3.34); no internal energy (isothermal DPD): no such limit
  out.fluctuation_number = has_energy ? particle::fluctuation_stability_number(p) : std::nan("");
  out.stable = p.dt < out.dt_critical &&
               (!has_energy || out.fluctuation_number < c.stability.fluctuation_number);
  return out;
}

// Which particle in an InstabilityError message went wrong, and how (particle/simulation.tpp:
// "unstable at step N (...): particle I x = (...) v = (...) u = U theta = ...; neighbours'
// theta: ...", or the cold heat slab's "took more energy than particle I ... (u = U)").
std::string classify_instability(const std::string& message) {
  if (message.find("took more energy than particle") != std::string::npos)
    return "negative_internal_energy";
  const auto start = message.find("): particle ");
  if (start == std::string::npos) return "unstable";
  std::string own = message.substr(start);
  own = own.substr(0, own.find("; neighbours")); // the failing particle's x, v, u, theta only
  own = own.substr(0, own.find(". Stability:"));
  std::string lower = own;
  std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
  if (lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos)
    return "non_finite";
  const auto u = own.find(" u = ");
  if (u != std::string::npos) {
    std::istringstream value(own.substr(u + 5));
    double energy = 0;
    if (value >> energy && !(energy > 0)) return "negative_internal_energy";
  }
  return "unstable";
}

// A finished particle run: non-finite results, energy drift, temperature off target, or stable.
void classify_summary(const CaseParameters& c, const fs::path& point_dir, io::Json& row) {
  io::Json summary = io::Json::object();
  try {
    summary = io::read_json(point_dir / "particle" / "summary.json");
  } catch (const io::InputError& e) {
    row["status"] = "failed";
    row["reason"] = e.what();
    return;
  }
  const bool has_energy = c.particle.energy == particle::EnergyModel::Dpde;
  const double drift = io::number(summary, {"results", "energy_relative_drift_max"});
  const double tk = io::number(summary, {"results", "T_kinetic"});
  const double ti = io::number(summary, {"results", "T_internal"});
  // Between thermal walls the fluid's mean temperature is neither the walls' mean (the denser
  // cold side exchanges more heat) nor steady in a short run (T_internal lags T_kinetic while
  // c_v relaxes): a run is held to the walls' temperature range. Otherwise to the target.
  const bool thermal_walls = c.scene.thermal_wall_mean() > 0;
  const std::array<double, 2> walls = thermal_wall_range(c.scene);
  const double target = run_target_temperature(c.scene, summary);
  const auto off = [&](double T) {
    return thermal_walls ? relative_distance_outside(T, walls) : std::abs(T / target - 1);
  };
  double error = off(tk);
  if (has_energy) error = std::max(error, off(ti));
  row["energy_relative_drift_max"] = number_or_null(drift);
  row["T_kinetic"] = number_or_null(tk);
  row["T_internal"] = number_or_null(ti);
  row["T_target"] = number_or_null(target);
  row["temperature_relative_error"] = number_or_null(error);
  const auto& bounds = c.stability;
  // JSON has no NaN: a non-finite result is written as null, read back here as NaN
  if (!std::isfinite(tk) || (has_energy && (!std::isfinite(ti) || !std::isfinite(drift)))) {
    row["status"] = "non_finite";
    row["reason"] = "non-finite T_kinetic, T_internal or energy drift in particle/summary.json";
  } else if (has_energy && drift > bounds.energy_drift) { // isothermal DPD conserves no energy
    row["status"] = "energy_drift";
    row["reason"] = "max |dE/E| = " + std::to_string(drift) + " > " +
                    std::to_string(bounds.energy_drift) + " (Compare/Stability/Energy drift bound)";
  } else if (error > bounds.temperature_tolerance) {
    row["status"] = "temperature_off";
    row["reason"] =
        "T_kinetic = " + std::to_string(tk) +
        (has_energy ? ", T_internal = " + std::to_string(ti) : std::string()) +
        (thermal_walls ? " outside the thermal walls' range [" + std::to_string(walls[0]) + ", " +
                             std::to_string(walls[1]) + "]"
                       : " against T_target = " + std::to_string(target)) +
        " (tolerance " + std::to_string(bounds.temperature_tolerance) + ")";
  } else {
    row["status"] = "stable";
    row["reason"] = "";
  }
}

const std::set<std::string> kInstabilities = {"non_finite", "negative_internal_energy", "unstable"};

} // namespace

int stability(const GridOptions& cl, const CaseReader& reader) {
  const std::vector<Axis> axes = parse_axes(cl, reader);
  if (axes.empty())
    throw io::InputError("stability needs at least one --vary 'Section/Key=V1,V2,...'");
  std::vector<Point> points = make_points(cl, reader, axes);

  Study s;
  s.name = "stability";
  s.child_command = "particle";
  s.columns_before_wall = {"dt",
                           "predicted_dt_critical",
                           "fluctuation_number",
                           "predicted_stable",
                           "energy_relative_drift_max",
                           "T_kinetic",
                           "T_internal",
                           "T_target",
                           "temperature_relative_error"};
  s.grid = grid_description(cl, reader, axes);
  for (auto& p : points) {
    if (!p.rejected.empty()) continue;
    const Prediction prediction = predict(p.resolved);
    p.columns["dt"] = p.resolved.particle.dt;
    p.columns["predicted_dt_critical"] = number_or_null(prediction.dt_critical);
    p.columns["fluctuation_number"] = number_or_null(prediction.fluctuation_number);
    p.columns["predicted_stable"] = prediction.stable;
  }

  s.finished = [&](const Point& p, const fs::path& point_dir, const io::Json* previous,
                   io::Json& row) {
    if (previous && kInstabilities.count(io::text(*previous, {"status"}))) {
      row = *previous; // a blow-up is a result: the same inputs blow up again
      return true;
    }
    if (!fs::exists(point_dir / "particle" / "summary.json")) return false;
    row["exit_code"] = 0;
    classify_summary(p.resolved, point_dir, row);
    return true;
  };
  s.describe = [&](const Point& p, const fs::path& point_dir, const ChildResult& r, io::Json& row) {
    if (r.exit_code == 0)
      classify_summary(p.resolved, point_dir, row);
    else if (r.exit_code == 4) // particle::InstabilityError
      row["status"] = classify_instability(r.message);
    else if (interrupted_exit(r.exit_code))
      row["status"] = "interrupted";
    else
      row["status"] = "failed";
  };
  return run_study(cl, s, points);
}

} // namespace twinflow::study
