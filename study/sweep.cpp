// twinflow sweep CASE --vary 'Section/Key=V1,V2' [--rayleigh R1,R2]: one paired run (`twinflow
// run`) per point of the grid, in child processes, and one table of their metrics.

#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>

#include "continuum/parameters.hpp"
#include "io/files.hpp"
#include "study/grid.hpp"
#include "study/sweeps.hpp"
#include "transport/coefficients.hpp"

namespace twinflow::study {

namespace fs = std::filesystem;

namespace {

// A point's run is complete when its comparison wrote metrics.json or, before the compare
// stage exists, when the continuum twin wrote its summary.
bool run_finished(const fs::path& point_dir) {
  if (fs::exists(point_dir / "compare" / "metrics.json")) return true;
  return !fs::exists(point_dir / "compare") && fs::exists(point_dir / "continuum" / "summary.json");
}

io::Json read_json_or_empty(const fs::path& file) {
  try {
    return io::read_json(file);
  } catch (const io::InputError&) { // missing or unreadable: its columns stay empty
    return io::Json::object();
  }
}

// The point's metrics as table columns: compare/metrics.json's "table_row", else the few
// numbers the particle and continuum summaries hold.
void add_metrics(const fs::path& point_dir, const std::set<std::string>& reserved, io::Json& row) {
  const auto put = [&](const std::string& key, const io::Json& value) {
    row[reserved.count(key) ? "compare_" + key : key] = value;
  };
  const fs::path metrics = point_dir / "compare" / "metrics.json";
  if (fs::exists(metrics)) {
    const io::Json recorded = read_json_or_empty(metrics);
    if (const io::Json* table_row = io::find(recorded, {"table_row"}))
      if (table_row->is_object())
        for (const auto& [key, value] : table_row->items()) put(key, value);
    return;
  }
  const io::Json continuum = read_json_or_empty(point_dir / "continuum" / "summary.json");
  put("rayleigh", number_or_null(io::number(continuum, {"dimensionless", "rayleigh"})));
  put("prandtl", number_or_null(io::number(continuum, {"dimensionless", "prandtl"})));
  put("nusselt_nominal",
      number_or_null(io::number(continuum, {"results", "nusselt_volume_average"})));
  put("wall_seconds_continuum", number_or_null(io::number(continuum, {"stage_wall_time_s"})));
  const io::Json particle = read_json_or_empty(point_dir / "particle" / "summary.json");
  put("wall_seconds_particle", number_or_null(io::number(particle, {"results", "wall_seconds"})));
  put("particle_steps", number_or_null(io::number(particle, {"results", "N"}) *
                                       (io::number(particle, {"results", "steps"}) +
                                        io::number(particle, {"results", "equilibration_steps"}))));
}

std::string status_of(int exit_code) {
  if (exit_code == 0) return "done";
  if (exit_code == kExitInterrupted || exit_code == 128 + SIGINT || exit_code == 128 + SIGTERM)
    return "interrupted";
  return "failed";
}

double magnitude(const std::array<double, 3>& v, int dim) {
  double s = 0;
  for (int d = 0; d < dim; ++d) s += v[d] * v[d];
  return std::sqrt(s);
}

// The gravity that gives `point` the target Ra with the reference coefficients, along the case's
// own gravity direction.
std::array<double, 3> gravity_for_rayleigh(const CaseParameters& point,
                                           const transport::Coefficients& k,
                                           double target_rayleigh) {
  continuum::ContinuumParameters c = point.continuum;
  c.viscosity.value_at_reference = k.viscosity.value;
  c.conductivity.value_at_reference = k.conductivity.value;
  c.heat_capacity = k.heat_capacity_p.value;
  c.thermal_expansion = k.thermal_expansion.value;
  const continuum::DimensionlessNumbers n = continuum::dimensionless_numbers(c);
  // the low-Mach ideal gas's alpha = 1/T_ref, as dimensionless_numbers takes it
  const double alpha =
      c.model == continuum::Model::LowMach ? 1 / c.reference_temperature : c.thermal_expansion;
  const double H = n.height, dT = std::abs(n.temperature_difference);
  // Boussinesq Ra definition, continuum/parameters.hpp dimensionless_numbers: Ra = g alpha dT
  // H^3 / (nu chi), nu = eta / (n m), chi = kappa / (n c_p)
  const double g =
      target_rayleigh * n.kinematic_viscosity * n.thermal_diffusivity / (alpha * dT * H * H * H);
  if (!(g > 0) || !std::isfinite(g))
    throw std::runtime_error("the reference coefficients give no finite gravity for Ra = " +
                             std::to_string(target_rayleigh) +
                             " (nu = " + std::to_string(n.kinematic_viscosity) +
                             ", chi = " + std::to_string(n.thermal_diffusivity) +
                             ", alpha = " + std::to_string(alpha) + ")");
  const double scale = g / magnitude(point.scene.gravity, point.scene.dim);
  std::array<double, 3> gravity{{0, 0, 0}};
  for (int d = 0; d < point.scene.dim; ++d) gravity[d] = scale * point.scene.gravity[d];
  return gravity;
}

std::string vector_text(const std::array<double, 3>& v, int dim) {
  std::string text;
  for (int d = 0; d < dim; ++d) {
    char component[32];
    std::snprintf(component, sizeof component, "%.10g", v[d]);
    text += (d ? ", " : "") + std::string(component);
  }
  return text;
}

} // namespace

int sweep(const GridOptions& cl, const CaseReader& reader) {
  const std::vector<Axis> axes = parse_axes(cl, reader);
  if (axes.empty() && cl.rayleigh.empty())
    throw io::InputError("sweep needs at least one --vary 'Section/Key=V1,V2,...' or "
                         "--rayleigh R1,R2,...");
  for (const auto& a : axes)
    if (a.key == "Scene/Gravity" && !cl.rayleigh.empty())
      throw io::InputError("--vary 'Scene/Gravity=...' and --rayleigh both set the gravity; "
                           "give one of them");
  const std::size_t copies = std::max<std::size_t>(1, cl.rayleigh.size());
  std::vector<Point> points = make_points(cl, reader, axes, copies);

  Study s;
  s.name = "sweep";
  s.child_command = "run";
  s.columns_before_wall = {"target_rayleigh", "gravity"};
  s.grid = io::Json::object();
  s.grid["case_file"] = fs::absolute(cl.case_file).lexically_normal().string();
  s.grid["base_parameters"] = reader.record(cl.settings);
  s.grid["vary"] = io::Json::object();
  std::set<std::string> reserved = {"point",           "status",  "reason",      "exit_code",
                                    "target_rayleigh", "gravity", "wall_seconds"};
  for (const auto& a : axes) {
    s.grid["vary"][a.key] = io::Json::array();
    for (const auto& v : a.shown) s.grid["vary"][a.key].push_back(v);
    reserved.insert(a.key);
  }
  s.grid["rayleigh"] = io::Json(cl.rayleigh);

  for (std::size_t i = 0; i < points.size(); ++i) {
    Point& p = points[i];
    p.columns["target_rayleigh"] =
        cl.rayleigh.empty() ? io::Json() : io::Json(cl.rayleigh[i % copies]);
    p.columns["gravity"] = p.rejected.empty()
                               ? io::Json(magnitude(p.resolved.scene.gravity, p.resolved.scene.dim))
                               : io::Json();
    if (cl.rayleigh.empty() || !p.rejected.empty()) continue;
    // What --rayleigh needs is checked before anything runs.
    const std::string where = cl.case_file + " (point " + p.name + ")";
    if (p.resolved.compare.rayleigh_control != "gravity")
      throw io::InputError(where + ": 'Compare/Rayleigh control' = '" +
                           p.resolved.compare.rayleigh_control + "'; allowed: gravity");
    if (!(magnitude(p.resolved.scene.gravity, p.resolved.scene.dim) > 0))
      throw io::InputError(where + ": --rayleigh scales the case's gravity, but 'Scene/Gravity' "
                                   "is zero; allowed: a non-zero gravity (its direction is kept)");
    if (continuum::dimensionless_numbers(p.resolved.continuum).heated_direction < 0)
      throw io::InputError(where + ": --rayleigh needs a heated direction (two thermal walls of "
                                   "one direction at different temperatures); the case has none");
  }
  std::set<std::string> varied_outside_gravity;
  for (const auto& a : axes)
    if (a.key.rfind("Particle/", 0) == 0 || a.key == "Scene/Density" ||
        a.key == "Scene/Temperature" || a.key.find("wall temperature") != std::string::npos ||
        a.key.rfind("Transport/", 0) == 0)
      varied_outside_gravity.insert(a.key);
  if (!cl.rayleigh.empty() && !varied_outside_gravity.empty())
    std::cerr << "sweep: note: --rayleigh takes the coefficients of the base case's reference "
                 "run; the varied '"
              << *varied_outside_gravity.begin()
              << "' may change them, so a point's continuum Ra may differ from its target\n";

  s.prepare = [&](const fs::path& dir) {
    if (cl.rayleigh.empty()) return 0;
    // The transport stage runs the bulk fluid without gravity: one run serves every target Ra.
    const fs::path reference = dir / "reference";
    const fs::path summary_file = reference / "transport" / "summary.json";
    if (!fs::exists(summary_file)) {
      fs::create_directories(reference);
      ChildTask t;
      t.arguments = {"transport", cl.case_file, "--out", reference.string()};
      for (const auto& o : cl.settings) t.arguments.insert(t.arguments.end(), {"--set", o});
      if (cl.run.threads > 0)
        t.arguments.insert(t.arguments.end(), {"--threads", std::to_string(cl.run.threads)});
      t.log = reference / "log.txt";
      std::cerr << "sweep: reference transport run for --rayleigh (log: " << t.log.string()
                << ")\n";
      ChildResult result;
      const int signal =
          run_children({t}, 1, [&](std::size_t, const ChildResult& r) { result = r; });
      if (signal || result.exit_code == kExitInterrupted) {
        std::cerr << "sweep: interrupted in the reference run; run the same command again\n";
        return kExitInterrupted;
      }
      if (result.exit_code != 0) {
        std::cerr << "twinflow: failed: the reference transport run (exit " << result.exit_code
                  << "): " << result.message << " (log: " << t.log.string() << ")\n";
        return 1;
      }
    }
    const io::Json summary = io::read_json(summary_file);
    for (std::size_t i = 0; i < points.size(); ++i) {
      Point& p = points[i];
      if (!p.rejected.empty()) continue;
      const transport::Coefficients k = transport::read_coefficients(
          summary, p.resolved.transport.source, p.resolved.continuum.reference_temperature);
      const auto g = gravity_for_rayleigh(p.resolved, k, cl.rayleigh[i % copies]);
      p.assignments.push_back("Scene/Gravity=" + vector_text(g, p.resolved.scene.dim));
      p.columns["gravity"] = magnitude(g, p.resolved.scene.dim);
    }
    return 0;
  };
  s.finished = [&](const Point&, const fs::path& point_dir, const io::Json*, io::Json& row) {
    if (!run_finished(point_dir)) return false;
    row["status"] = "done";
    row["exit_code"] = 0;
    add_metrics(point_dir, reserved, row);
    return true;
  };
  s.describe = [&](const Point&, const fs::path& point_dir, const ChildResult& r, io::Json& row) {
    row["status"] = status_of(r.exit_code);
    if (r.exit_code == 0) add_metrics(point_dir, reserved, row);
  };
  return run_study(cl, s, points);
}

} // namespace twinflow::study
