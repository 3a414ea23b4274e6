#include "study/grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "io/files.hpp"
#include "study/stages.hpp"

// The grid's table (DIR/<command>.csv and .json, written after every point) and run_study, which
// decides what runs (resuming an earlier grid), spreads the points and records what they did.
namespace twinflow::study {

namespace fs = std::filesystem;

io::Json number_or_null(double v) {
  return std::isfinite(v) ? io::Json(v) : io::Json();
}

namespace {

std::string csv_cell(const io::Json* v) {
  if (!v || v->is_null()) return "";
  if (v->is_number()) {
    if (!std::isfinite(v->get<double>())) return "";
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", v->get<double>());
    return text;
  }
  std::string s = v->is_string() ? v->get<std::string>() : v->dump(); // true, false
  if (s.size() > 200) s = s.substr(0, 200) + "... (see log.txt)";
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (const char ch : s) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return quoted + "\"";
}

std::string duration_text(double seconds) {
  const long s = std::lround(seconds);
  if (s < 60) return std::to_string(s) + "s";
  if (s < 3600) return std::to_string(s / 60) + "m" + std::to_string(s % 60) + "s";
  return std::to_string(s / 3600) + "h" + std::to_string(s % 3600 / 60) + "m";
}

// Columns: the fixed ones, then every other key of the rows, sorted.
std::vector<std::string> table_columns(const Study& s, const std::vector<std::string>& varied,
                                       const std::vector<io::Json>& rows) {
  std::vector<std::string> columns = {"point", "status", "reason", "exit_code"};
  columns.insert(columns.end(), varied.begin(), varied.end());
  columns.insert(columns.end(), s.columns_before_wall.begin(), s.columns_before_wall.end());
  columns.push_back("wall_seconds");
  columns.insert(columns.end(), s.columns_after_wall.begin(), s.columns_after_wall.end());
  const std::set<std::string> fixed(columns.begin(), columns.end());
  std::set<std::string> others;
  for (const auto& row : rows)
    for (const auto& [key, value] : row.items())
      if (!fixed.count(key)) others.insert(key);
  columns.insert(columns.end(), others.begin(), others.end());
  return columns;
}

void write_table(const fs::path& dir, const Study& s, const std::string& launcher,
                 const std::vector<std::string>& varied, const std::vector<Point>& points,
                 const std::vector<io::Json>& rows) {
  const auto columns = table_columns(s, varied, rows);
  std::ostringstream csv;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const io::Json header(columns[c]);
    csv << (c ? "," : "") << csv_cell(&header);
  }
  csv << "\n";
  io::Json json = io::Json::object();
  json["command"] = s.name;
  json["grid"] = s.grid;
  // Not part of the grid: the answers do not depend on the ranks (a resumed grid may change it).
  json["launcher"] = launcher.empty() ? io::Json() : io::Json(launcher);
  json["columns"] = io::Json::array();
  for (const auto& c : columns) json["columns"].push_back(c);
  json["points"] = io::Json::array();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t c = 0; c < columns.size(); ++c)
      csv << (c ? "," : "") << csv_cell(io::find(rows[i], {columns[c]}));
    csv << "\n";
    io::Json point = io::Json::object();
    point["row"] = rows[i];
    point["set"] = io::Json::array();
    for (const auto& a : points[i].assignments) point["set"].push_back(a);
    point["log"] = "points/" + points[i].name + "/log.txt";
    point["command"] = points[i].command.empty() ? io::Json() : io::Json(points[i].command);
    json["points"].push_back(point);
  }
  io::write_file_atomically(dir / (s.name + ".csv"), csv.str());
  io::write_file_atomically(dir / (s.name + ".json"), io::dump(json));
}

bool has_stage_folder(const fs::path& point_dir) {
  for (const char* stage : {"particle", "transport", "continuum", "compare"})
    if (fs::exists(point_dir / stage)) return true;
  return false;
}

} // namespace

namespace {
// What an earlier invocation left in DIR: its rows and commands, by point name.
struct PreviousGrid {
  std::map<std::string, io::Json> rows;
  std::map<std::string, std::string> commands;
};

// Everything is decided before the first write: a refused directory stays untouched.
PreviousGrid read_previous_grid(const GridOptions& o, const Study& s, const fs::path& dir) {
  const fs::path json_path = dir / (s.name + ".json");
  if (fs::exists(dir) && !fs::is_directory(dir))
    throw io::InputError(dir.string() + ": exists and is not a directory");
  PreviousGrid previous;
  if (fs::exists(json_path) && !o.run.force) {
    io::Json old;
    try {
      old = io::read_json(json_path);
    } catch (const io::InputError&) {
      throw io::InputError(json_path.string() +
                           ": unreadable; use --force to start afresh or another --out");
    }
    const io::Json* grid = io::find(old, {"grid"});
    if (!grid || *grid != s.grid)
      throw io::InputError(json_path.string() + ": holds another grid (case file, its " +
                           "parameters, --set, --vary or --rayleigh differ); use --force to " +
                           "start afresh (deletes its points) or another --out");
    if (const io::Json* old_points = io::find(old, {"points"}))
      for (const auto& p : *old_points)
        if (const io::Json* row = io::find(p, {"row"}); row && io::find(*row, {"point"})) {
          previous.rows[io::text(*row, {"point"})] = *row;
          previous.commands[io::text(*row, {"point"})] = io::text(p, {"command"});
        }
  } else if (fs::exists(dir) && !fs::is_empty(dir) && !o.run.force) {
    throw io::InputError(dir.string() + ": exists and holds no " + s.name +
                         ".json; use --force to use it anyway or another --out");
  }
  return previous;
}

// The rows and the children still to run: earlier results stand, rejected points are failed.
struct Plan {
  std::vector<io::Json> rows;
  std::vector<ChildTask> tasks;
  std::vector<std::size_t> task_point; // the point each task runs
  std::vector<bool> restarted;         // continues a particle run from its checkpoint
  std::size_t settled = 0;             // points already decided
};

// The child's command line for a point: the stage, the case, the user's and the point's --set,
// and --restart (a checkpoint) or --force (a run cut short after its particle stage).
ChildTask point_task(const GridOptions& o, const Study& s, const Point& p, const fs::path& dir) {
  const fs::path point_dir = dir / "points" / p.name;
  ChildTask t;
  t.arguments = {s.child_command, o.case_file, "--out", point_dir.string()};
  for (const auto& a : o.settings) t.arguments.insert(t.arguments.end(), {"--set", a});
  for (const auto& a : p.assignments) t.arguments.insert(t.arguments.end(), {"--set", a});
  if (fs::exists(particle_checkpoint(point_dir)))
    t.arguments.push_back("--restart");
  else if (has_stage_folder(point_dir))
    t.arguments.push_back("--force");
  t.log = point_dir / "log.txt";
  t.launcher = o.launcher;
  return t;
}

Plan plan_points(const GridOptions& o, const Study& s, std::vector<Point>& points,
                 const std::vector<std::string>& varied, const fs::path& dir,
                 PreviousGrid& previous, bool afresh) {
  Plan plan;
  plan.rows.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    io::Json& row = plan.rows[i];
    row["point"] = p.name;
    row["status"] = "pending";
    row["reason"] = "";
    row["exit_code"] = io::Json();
    for (std::size_t a = 0; a < varied.size(); ++a)
      row[varied[a]] = s.grid.at("vary").at(varied[a]).at(p.value_index[a]);
    for (const auto& [key, value] : p.columns.items()) row[key] = value;
    const auto prev = previous.rows.find(p.name);
    const io::Json* previous_row = prev == previous.rows.end() ? nullptr : &prev->second;
    row["wall_seconds"] =
        previous_row ? previous_row->value("wall_seconds", io::Json()) : io::Json();
    if (!p.rejected.empty()) {
      row["status"] = "failed", row["exit_code"] = 2, row["reason"] = p.rejected;
      ++plan.settled;
      continue;
    }
    if (!afresh && s.finished(p, dir / "points" / p.name, previous_row, row)) {
      points[i].command = previous.commands[p.name];
      std::cerr << s.name << ": point " << p.name
                << " skipped (finished earlier: " << io::text(row, {"status"}) << ")\n";
      ++plan.settled;
      continue;
    }
    plan.tasks.push_back(point_task(o, s, p, dir));
    plan.task_point.push_back(i);
    plan.restarted.push_back(fs::exists(particle_checkpoint(dir / "points" / p.name)));
  }
  return plan;
}

// Points at once and threads each: --jobs, else one per core (a launcher places the points'
// processes itself: one at a time unless --jobs says); threads 1 when points run side by side.
struct Spread {
  int jobs = 1, threads = 0; // threads 0: the child's default
};
Spread spread_points(const GridOptions& o, std::size_t tasks) {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  Spread sp;
  sp.jobs = o.jobs > 0            ? o.jobs
            : !o.launcher.empty() ? 1
                                  : std::max(1, cores / std::max(1, o.run.threads));
  sp.jobs = std::max(1, std::min<int>(sp.jobs, static_cast<int>(tasks)));
  sp.threads = o.run.threads > 0 ? o.run.threads : sp.jobs > 1 && !o.plan ? 1 : 0;
  return sp;
}

// --plan: each point's command as a script, for a scheduler to run (docs/cluster.md).
void write_plan_scripts(const GridOptions& o, const Study& s, const std::vector<Point>& points,
                        const Plan& plan, const fs::path& dir) {
  for (const Point& p : points) // an earlier plan's script of a point finished since
    fs::remove(dir / "points" / p.name / "command.sh");
  for (const std::size_t i : plan.task_point) {
    const Point& p = points[i];
    const fs::path script = dir / "points" / p.name / "command.sh";
    io::write_file_atomically(script, "#!/bin/sh\n# " + s.name + " point " + p.name + " (" +
                                          s.name + " --plan): run it, then the same " + s.name +
                                          " command again for the table\n" +
                                          (o.launcher.empty() ? "exec " : "") + p.command + "\n");
    fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
  }
  std::cerr << s.name << ": planned " << plan.tasks.size() << " of " << points.size()
            << " points, nothing run: DIR/points/NNN/command.sh each (DIR = " << dir.string()
            << "); the same command without --plan then skips the finished ones and writes "
               "the table\n";
}

// Runs the planned children, recording each point's row as it ends; returns the signal that
// stopped the grid (0: none).
int run_points(const GridOptions& o, Study& s, std::vector<Point>& points, Plan& plan,
               const std::vector<std::string>& varied, const fs::path& dir, const Spread& sp) {
  double wall_sum = 0;
  std::size_t done_now = 0;
  return run_children(plan.tasks, sp.jobs, [&](std::size_t t, const ChildResult& result) {
    const std::size_t i = plan.task_point[t];
    io::Json& row = plan.rows[i];
    const fs::path point_dir = dir / "points" / points[i].name;
    row["exit_code"] = result.exit_code;
    row["reason"] = result.exit_code == 0 ? "" : result.message;
    s.describe(points[i], point_dir, result, row);
    // A launcher may end with its own code when stopped (mpirun: 1, whatever its ranks said):
    // a point stopped by the forwarded signal that left a checkpoint was interrupted.
    if (result.stopped && result.exit_code != 0 && fs::exists(particle_checkpoint(point_dir)))
      row["status"] = "interrupted";
    // A continued particle run adds to the wall time of its earlier attempts.
    const double before = io::number(row, {"wall_seconds"});
    const double earlier = plan.restarted[t] && std::isfinite(before) ? before : 0;
    row["wall_seconds"] = earlier + result.wall_seconds;
    write_table(dir, s, o.launcher, varied, points, plan.rows);
    wall_sum += result.wall_seconds;
    ++done_now;
    ++plan.settled;
    const double eta =
        wall_sum / done_now * static_cast<double>(plan.tasks.size() - done_now) / sp.jobs;
    std::cerr << s.name << ": point " << plan.settled << "/" << points.size() << " done ("
              << io::text(row, {"status"}) << "), ETA "
              << (done_now == plan.tasks.size() ? "0s" : duration_text(eta)) << "\n";
  });
}

void print_counts(const Study& s, const std::vector<io::Json>& rows, const fs::path& dir) {
  std::map<std::string, int> counts;
  for (const auto& row : rows) ++counts[io::text(row, {"status"})];
  std::cerr << s.name << ":";
  for (const auto& [status, n] : counts) std::cerr << " " << n << " " << status;
  std::cerr << "; table: " << (dir / (s.name + ".csv")).string() << "\n";
}
} // namespace

int run_study(const GridOptions& o, Study& s, std::vector<Point>& points) {
  const fs::path dir =
      o.run.out.empty()
          ? fs::path("twinflow-runs") / (fs::path(o.case_file).stem().string() + "-" + s.name)
          : o.run.out;
  std::vector<std::string> varied;
  for (const auto& [key, values] : s.grid.at("vary").items()) varied.push_back(key);
  PreviousGrid previous = read_previous_grid(o, s, dir);
  const bool afresh = o.run.force;
  if (afresh) // only what a grid writes
    for (const char* owned : {"points", "reference"}) fs::remove_all(dir / owned);
  fs::create_directories(dir / "points");
  if (s.prepare)
    if (const int rc = s.prepare(dir)) return rc;

  Plan plan = plan_points(o, s, points, varied, dir, previous, afresh);
  const Spread sp = spread_points(o, plan.tasks.size());
  for (std::size_t t = 0; t < plan.tasks.size(); ++t) {
    if (sp.threads > 0)
      plan.tasks[t].arguments.insert(plan.tasks[t].arguments.end(),
                                     {"--threads", std::to_string(sp.threads)});
    fs::create_directories(plan.tasks[t].log.parent_path());
    points[plan.task_point[t]].command = task_command(plan.tasks[t]);
  }
  write_table(dir, s, o.launcher, varied, points, plan.rows);
  if (o.plan) {
    write_plan_scripts(o, s, points, plan, dir);
    return 0;
  }
  std::cerr << s.name << ": " << points.size() << " points, " << plan.tasks.size() << " to run, "
            << sp.jobs << " at a time"
            << (sp.threads > 0 ? ", " + std::to_string(sp.threads) + " thread(s) each" : "")
            << (o.launcher.empty() ? "" : ", each under '" + o.launcher + "'")
            << "; table: " << (dir / (s.name + ".csv")).string() << "\n";
  const int signal = run_points(o, s, points, plan, varied, dir, sp);
  print_counts(s, plan.rows, dir);
  if (signal) {
    std::cerr << s.name << ": interrupted by a signal; run the same command again to continue\n";
    return kExitInterrupted;
  }
  write_report(dir);
  return 0;
}

} // namespace twinflow::study
