// twinflow sweep CASE --vary 'Section/Key=V1,V2' [--rayleigh R1,R2]: one paired run (`twinflow
// run`) per point of the grid, in child processes, and one table of their metrics.

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>

#include "continuum/parameters.hpp"
#include "io/files.hpp"
#include "study/grid.hpp"
#include "study/stages.hpp"
#include "study/sweeps.hpp"
#include "study/twin_coefficients.hpp"
#include "transport/coefficients.hpp"

namespace twinflow::study {

namespace fs = std::filesystem;

namespace {

// How far a point's twin may land from its target Ra (issue 31's acceptance); by construction
// it lands exactly, so a miss means its coefficients changed after its gravity was set.
constexpr double kRayleighTolerance = 0.03;

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
  if (interrupted_exit(exit_code)) return "interrupted";
  return "failed";
}

double magnitude(const std::array<double, 3>& v, int dim) {
  double s = 0;
  for (int d = 0; d < dim; ++d) s += v[d] * v[d];
  return std::sqrt(s);
}

// Scales the case's gravity (its direction kept) so that the twin `twin` (the point's continuum
// parameters with the coefficients it will take) runs at the target Ra. Throws std::runtime_error
// when no gravity does.
std::array<double, 3> gravity_for_rayleigh(const continuum::ContinuumParameters& twin,
                                           double target_rayleigh) {
  const continuum::DimensionlessNumbers n = continuum::dimensionless_numbers(twin);
  // Ra = g alpha dT H^3 / (nu chi) is proportional to |g| (de Vahl Davis 1983, eq. 5)
  const double scale = target_rayleigh / n.rayleigh;
  if (!(scale > 0) || !std::isfinite(scale))
    throw std::runtime_error(
        "no gravity gives Ra = " + number_text(target_rayleigh) + ": at the case's gravity the " +
        "twin's Ra is " + number_text(n.rayleigh) + " (nu = " + number_text(n.kinematic_viscosity) +
        ", chi = " + number_text(n.thermal_diffusivity) +
        ", dT = " + number_text(n.temperature_difference) + ")");
  std::array<double, 3> gravity{{0, 0, 0}};
  for (int d = 0; d < twin.dim; ++d) gravity[d] = scale * twin.gravity[d];
  return gravity;
}

// True when the point's twin takes the transport stage's coefficients, as `run` decides
// (study/run.cpp, chooses_coefficient_source).
bool twin_takes_transport(const GridOptions& cl, const Point& p) {
  return p.resolved.twin.coefficients_from_transport ||
         (!chooses_coefficient_source(cl.settings) && !chooses_coefficient_source(p.assignments));
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

// The grid as a sweep records it: what makes two invocations the same grid (case, parameters,
// --vary, --rayleigh) and the columns the points fill.
Study sweep_study(const GridOptions& cl, const CaseReader& reader, const std::vector<Axis>& axes) {
  Study s;
  s.name = "sweep";
  s.child_command = "run";
  // The achieved Ra (the nominal twin's) beside the target.
  s.columns_before_wall = {"target_rayleigh", "gravity"};
  if (!cl.rayleigh.empty()) s.columns_before_wall = {"target_rayleigh", "rayleigh", "gravity"};
  s.grid = grid_description(cl, reader, axes);
  s.grid["rayleigh"] = io::Json(cl.rayleigh);
  return s;
}

// Each point's target Ra and gravity columns; what --rayleigh needs of a point is checked before
// anything runs.
void set_rayleigh_columns(const GridOptions& cl, std::vector<Point>& points, std::size_t copies) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    Point& p = points[i];
    p.columns["target_rayleigh"] =
        cl.rayleigh.empty() ? io::Json() : io::Json(cl.rayleigh[i % copies]);
    p.columns["gravity"] = p.rejected.empty()
                               ? io::Json(magnitude(p.resolved.scene.gravity, p.resolved.scene.dim))
                               : io::Json();
    if (cl.rayleigh.empty() || !p.rejected.empty()) continue;
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
}

// The twin's coefficients must be known before the point's particle run sets g. `run` measures
// them at the particle fluid's mean temperature, known only after that run: here each point's
// transport stage is pinned to Scene/Temperature instead (unless the case or the grid gives
// Transport/Temperature), so that it can run first.
void pin_transport_temperatures(const GridOptions& cl, std::vector<Point>& points) {
  std::string pinned_note;
  for (Point& p : points) {
    if (cl.rayleigh.empty() || !p.rejected.empty() || !twin_takes_transport(cl, p) ||
        p.resolved.transport.temperature > 0)
      continue;
    p.resolved.transport.temperature = p.resolved.scene.temperature;
    p.assignments.push_back("Transport/Temperature=" + number_text(p.resolved.scene.temperature));
    pinned_note = p.assignments.back();
  }
  if (!pinned_note.empty())
    std::cerr << "sweep: --rayleigh sets g from each point's coefficients before its particle run, "
                 "so they are measured at the case's Scene/Temperature, not at the particle "
                 "fluid's mean temperature as `run` does: "
              << pinned_note << " (--set Transport/Temperature=... chooses another)\n";
}

// The point's own transport stage, with the inputs its run's will have (gravity is none of
// them): that run takes this measurement from the cache, or repeats it bit for bit. Returns the
// child's exit code (kExitInterrupted when stopped by a signal); its summary lands in
// `reference`/transport.
int run_reference_transport(const GridOptions& cl, Point& p, const fs::path& reference) {
  fs::create_directories(reference);
  ChildTask t;
  t.arguments = {"transport", cl.case_file, "--out", reference.string()};
  for (const auto& o : cl.settings) t.arguments.insert(t.arguments.end(), {"--set", o});
  for (const auto& a : p.assignments) t.arguments.insert(t.arguments.end(), {"--set", a});
  if (cl.run.threads > 0)
    t.arguments.insert(t.arguments.end(), {"--threads", std::to_string(cl.run.threads)});
  t.log = reference / "log.txt";
  t.launcher = cl.launcher; // the transport stage's particle runs use its ranks too
  std::cerr << "sweep: point " << p.name
            << ": its transport stage, for its gravity (log: " << t.log.string() << ")\n";
  ChildResult result;
  const int signal = run_children({t}, 1, [&](std::size_t, const ChildResult& r) { result = r; });
  if (signal || result.exit_code == kExitInterrupted) return kExitInterrupted;
  if (result.exit_code != 0)
    p.rejected = "its transport stage failed (exit " + std::to_string(result.exit_code) +
                 "): " + result.message + " (log: " + t.log.string() + ")";
  return result.exit_code;
}

// --rayleigh: each point's gravity from its twin's coefficients (its reference transport stage),
// so that the twin runs at the target Ra.
int set_rayleigh_gravities(const GridOptions& cl, std::vector<Point>& points, std::size_t copies,
                           const fs::path& dir) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    Point& p = points[i];
    if (cl.rayleigh.empty() || !p.rejected.empty()) continue;
    continuum::ContinuumParameters twin = p.resolved.continuum;
    if (twin_takes_transport(cl, p)) {
      const fs::path reference = dir / "reference" / p.name;
      const fs::path summary_file = reference / "transport" / "summary.json";
      if (!fs::exists(summary_file)) {
        const int rc = run_reference_transport(cl, p, reference);
        if (rc == kExitInterrupted) {
          std::cerr << "sweep: interrupted in a transport stage; run the same command again\n";
          return kExitInterrupted;
        }
        if (rc != 0) {
          p.columns["gravity"] = io::Json();
          continue;
        }
      }
      const transport::Coefficients k = transport::read_coefficients(
          io::read_json(summary_file), p.resolved.transport.source, twin.reference_temperature);
      take_coefficients(k, twin);
    }
    try {
      const auto g = gravity_for_rayleigh(twin, cl.rayleigh[i % copies]);
      p.assignments.push_back("Scene/Gravity=" + vector_text(g, p.resolved.scene.dim));
      p.columns["gravity"] = magnitude(g, p.resolved.scene.dim);
    } catch (const std::runtime_error& e) {
      p.rejected = e.what();
      p.columns["gravity"] = io::Json();
    }
  }
  return 0;
}

// A point lands when its twin's Ra is within kRayleighTolerance of the target. Its particle
// fluid's mean temperature is recorded beside: the coefficients were pinned to another.
void check_landing(const Point& p, const fs::path& point_dir, io::Json& row) {
  const double target = io::number(p.columns, {"target_rayleigh"});
  if (!std::isfinite(target) || io::text(row, {"status"}) != "done") return;
  row["transport_temperature"] = p.resolved.transport.temperature;
  row["particle_temperature"] = number_or_null(io::number(
      read_json_or_empty(point_dir / "particle" / "summary.json"), {"results", "T_kinetic"}));
  const double achieved = io::number(row, {"rayleigh"});
  if (std::isfinite(achieved) && std::fabs(achieved / target - 1) <= kRayleighTolerance) return;
  row["status"] = "failed";
  row["reason"] = std::isfinite(achieved)
                      ? "the twin ran at Ra = " + number_text(achieved) + ", " +
                            number_text(100 * (achieved / target - 1)) + "% from the target " +
                            number_text(target) +
                            " (allowed: " + number_text(100 * kRayleighTolerance) +
                            "%): its coefficients are not those its gravity was set with"
                      : "the twin recorded no Ra to compare with the target";
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
  Study s = sweep_study(cl, reader, axes);
  std::set<std::string> reserved = {"point",           "status",  "reason",      "exit_code",
                                    "target_rayleigh", "gravity", "wall_seconds"};
  for (const auto& a : axes) reserved.insert(a.key);
  set_rayleigh_columns(cl, points, copies);
  pin_transport_temperatures(cl, points);
  s.prepare = [&](const fs::path& dir) { return set_rayleigh_gravities(cl, points, copies, dir); };
  s.finished = [&](const Point& p, const fs::path& point_dir, const io::Json*, io::Json& row) {
    if (!run_finished(point_dir)) return false;
    row["status"] = "done";
    row["exit_code"] = 0;
    add_metrics(point_dir, reserved, row);
    check_landing(p, point_dir, row);
    return true;
  };
  s.describe = [&](const Point& p, const fs::path& point_dir, const ChildResult& r, io::Json& row) {
    row["status"] = status_of(r.exit_code);
    if (r.exit_code == 0) add_metrics(point_dir, reserved, row);
    check_landing(p, point_dir, row);
  };
  return run_study(cl, s, points);
}

} // namespace twinflow::study
