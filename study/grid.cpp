#include "study/grid.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io/files.hpp"
#include "study/stages.hpp"

extern char** environ;

namespace twinflow::study {

namespace fs = std::filesystem;

namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

// "Particle / Time step" -> "Particle/Time step", as the case's --set reads it.
std::string canonical_key(const std::string& text) {
  std::string key, part;
  std::istringstream parts(text);
  while (std::getline(parts, part, '/')) key += (key.empty() ? "" : "/") + trim(part);
  return key;
}

std::vector<std::string> split_items(const std::string& list) {
  std::vector<std::string> items;
  std::string item;
  std::istringstream s(list);
  while (std::getline(s, item, ',')) items.push_back(trim(item));
  if (!list.empty() && list.back() == ',') items.emplace_back(); // "a,b," has an empty last item
  return items;
}

// "0 -0.01" -> "0, -0.01": a vector value's components, as the case's lists take them.
std::string joined_components(const std::string& item) {
  std::istringstream s(item);
  std::string component, out;
  while (s >> component) out += (out.empty() ? "" : ", ") + component;
  return out;
}

// Reads the case with these assignments; returns the message of the first error ("" if none).
std::string read_error(const GridOptions& o, const CaseReader& reader,
                       const std::vector<std::string>& extra) {
  std::vector<std::string> settings = o.settings;
  settings.insert(settings.end(), extra.begin(), extra.end());
  try {
    reader.check(settings);
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

} // namespace

std::vector<Axis> parse_axes(const GridOptions& o, const CaseReader& reader) {
  reader.check(
      o.settings); // the case file and the user's --set first: their errors name themselves
  std::vector<Axis> axes;
  for (const auto& text : o.vary) {
    const std::string where = "--vary '" + text + "'";
    const auto eq = text.find('=');
    if (eq == std::string::npos || trim(text.substr(0, eq)).empty())
      throw io::InputError(where + ": expected 'Section/Key=V1,V2,...'");
    Axis axis;
    axis.key = canonical_key(text.substr(0, eq));
    for (const auto& other : axes)
      if (other.key == axis.key)
        throw io::InputError(where + ": '" + axis.key +
                             "' is varied twice; give all its values in one --vary");
    for (const auto& item : split_items(text.substr(eq + 1))) {
      if (item.empty())
        throw io::InputError(where + ": an empty value; allowed: values separated by commas, " +
                             "vector components by spaces ('Scene/Gravity=0 -0.01,0 -0.02')");
      std::string value = item;
      std::string error = read_error(o, reader, {axis.key + "=" + value});
      if (!error.empty() && item.find_first_of(" \t") != std::string::npos &&
          read_error(o, reader, {axis.key + "=" + joined_components(item)}).empty()) {
        value = joined_components(item); // a vector value: components were separated by spaces
        error.clear();
      }
      if (!error.empty()) {
        // Name the --vary option rather than the --set it became.
        const std::string as_set = "--set " + axis.key + "=" + value + ": ";
        if (error.rfind(as_set, 0) == 0) error = error.substr(as_set.size());
        throw io::InputError(where + " (value '" + item + "'): " + error);
      }
      axis.shown.push_back(item);
      axis.values.push_back(value);
    }
    axes.push_back(axis);
  }
  return axes;
}

std::vector<Point> make_points(const GridOptions& o, const CaseReader& reader,
                               const std::vector<Axis>& axes, std::size_t copies) {
  std::size_t combinations = 1;
  for (const auto& a : axes) combinations *= a.values.size();
  const std::size_t total = combinations * copies;
  const std::size_t width = std::max<std::size_t>(3, std::to_string(total - 1).size());
  std::vector<Point> points;
  std::size_t rejected = 0;
  for (std::size_t combination = 0; combination < combinations; ++combination) {
    Point p;
    p.value_index.resize(axes.size());
    std::size_t rest = combination;
    for (std::size_t a = axes.size(); a-- > 0;) { // the first axis varies slowest
      p.value_index[a] = rest % axes[a].values.size();
      rest /= axes[a].values.size();
    }
    for (std::size_t a = 0; a < axes.size(); ++a)
      p.assignments.push_back(axes[a].key + "=" + axes[a].values[p.value_index[a]]);
    std::vector<std::string> settings = o.settings;
    settings.insert(settings.end(), p.assignments.begin(), p.assignments.end());
    try { // every value passed on its own (parse_axes): only their combination can fail
      p.resolved = reader.load(settings).parameters;
    } catch (const io::InputError& e) {
      p.rejected = e.what();
      for (const auto& a : p.assignments) // name the --vary the value came from
        if (p.rejected.rfind("--set " + a + ": ", 0) == 0)
          p.rejected = "--vary " + p.rejected.substr(6);
      ++rejected;
    }
    for (std::size_t copy = 0; copy < copies; ++copy) {
      std::string name = std::to_string(points.size());
      p.name = std::string(width - name.size(), '0') + name;
      points.push_back(p);
    }
  }
  if (rejected == combinations)
    throw io::InputError("no point of the grid is a valid case; the first: " +
                         points.front().rejected);
  return points;
}

std::string shell_quoted(const std::string& word) {
  if (!word.empty() &&
      word.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789"
                             "_-./=:,+@%") == std::string::npos)
    return word;
  std::string out = "'";
  for (char ch : word) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

namespace {

constexpr const char* kCommandPlaceholder = "{cmd}";

std::vector<std::string>& environment_before_mpi() {
  static std::vector<std::string> saved;
  return saved;
}

// The template's first word when it names a program to run (not a shell builtin or keyword, an
// assignment, a quoted or expanded word, or {cmd} itself), else "".
std::string launcher_program(const std::string& launcher) {
  static const std::set<std::string> shell_words = {
      ".",     ":", "cd", "command", "eval", "exec",   "exit",  "export", "if",    "for",
      "while", "{", "!",  "set",     "time", "ulimit", "umask", "true",   "false", "case"};
  std::istringstream words(launcher);
  std::string first;
  words >> first;
  if (first.empty() || first.find(kCommandPlaceholder) != std::string::npos ||
      first.find_first_of("'\"\\$`=;&|()<>*?[~") != std::string::npos || shell_words.count(first))
    return "";
  return first;
}

bool executable_file(const fs::path& file) {
  std::error_code error;
  return fs::is_regular_file(file, error) && access(file.c_str(), X_OK) == 0;
}

bool found_on_path(const std::string& program) {
  if (program.find('/') != std::string::npos) return executable_file(program);
  const char* path = std::getenv("PATH");
  std::istringstream directories(path ? path : "/usr/bin:/bin");
  for (std::string directory; std::getline(directories, directory, ':');)
    if (executable_file(fs::path(directory.empty() ? "." : directory) / program)) return true;
  return false;
}

// This binary's absolute path: a launcher starts it elsewhere than in this process.
std::string this_binary() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? std::string("twinflow") : self.string();
}

// A child's files: stdin from /dev/null, stdout and stderr both into `out` (opened with `flags`).
class ChildFiles {
public:
  ChildFiles(const char* out, int flags) {
    posix_spawn_file_actions_init(&actions_);
    posix_spawn_file_actions_addopen(&actions_, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions_, 1, out, flags, 0644);
    posix_spawn_file_actions_adddup2(&actions_, 1, 2);
  }
  ~ChildFiles() { posix_spawn_file_actions_destroy(&actions_); }
  ChildFiles(const ChildFiles&) = delete;
  ChildFiles& operator=(const ChildFiles&) = delete;
  const posix_spawn_file_actions_t* get() const { return &actions_; }

private:
  posix_spawn_file_actions_t actions_;
};

// argv for posix_spawn: pointers into `words`, null-terminated.
std::vector<char*> argv_of(std::vector<std::string>& words) {
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  return argv;
}

// Runs `sh -n -c TEXT` (parse only); true when the shell accepts its syntax.
bool valid_shell_syntax(const std::string& text) {
  std::vector<std::string> words = {"sh", "-n", "-c", text};
  const std::vector<char*> argv = argv_of(words);
  const ChildFiles files("/dev/null", O_WRONLY);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, "/bin/sh", files.get(), nullptr, argv.data(), environ);
  if (rc != 0) return true; // no shell to ask: the points will say
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

} // namespace

void check_launcher(const std::string& launcher) {
  const std::string allowed = "allowed: a command with {cmd} once where each point's command "
                              "goes, e.g. 'mpirun -np 2 {cmd}' or 'srun -n 4 {cmd}'";
  if (launcher.find_first_of("\n\r") != std::string::npos)
    throw io::InputError("--launcher: the template spans several lines; " + allowed);
  const std::string where = "--launcher '" + launcher + "'";
  std::size_t placeholders = 0;
  for (auto at = launcher.find(kCommandPlaceholder); at != std::string::npos;
       at = launcher.find(kCommandPlaceholder, at + 1))
    ++placeholders;
  if (placeholders != 1)
    throw io::InputError(where + ": " +
                         (placeholders ? "{cmd} " + std::to_string(placeholders) + " times"
                                       : std::string("no {cmd}")) +
                         "; " + allowed);
  if (!valid_shell_syntax(launched_command(launcher, {"particle"})))
    throw io::InputError(
        where + ": not valid shell syntax (sh -n refuses it: an unclosed quote?); " + allowed);
  const std::string program = launcher_program(launcher);
  if (!program.empty() && !found_on_path(program))
    throw io::InputError(where + ": '" + program + "' not found (not an executable on PATH)");
}

std::string launched_command(const std::string& launcher,
                             const std::vector<std::string>& arguments) {
  std::string command = shell_quoted(this_binary());
  for (const auto& a : arguments) command += " " + shell_quoted(a);
  std::string text = launcher;
  text.replace(text.find(kCommandPlaceholder), std::string(kCommandPlaceholder).size(), command);
  return launcher_program(launcher).empty() ? text : "exec " + text;
}

void save_environment_before_mpi() {
  auto& saved = environment_before_mpi();
  saved.clear();
  for (char** v = environ; *v; ++v) saved.emplace_back(*v);
}

std::string task_command(const ChildTask& task) {
  if (!task.launcher.empty()) return launched_command(task.launcher, task.arguments);
  std::string command = shell_quoted(this_binary());
  for (const auto& a : task.arguments) command += " " + shell_quoted(a);
  return command;
}

namespace {

volatile std::sig_atomic_t signals_received = 0;
volatile std::sig_atomic_t last_signal = 0;
extern "C" void on_grid_stop_signal(int sig) { // C linkage: one name per program
  last_signal = sig;
  signals_received = signals_received + 1;
}

// This binary again, in its own process group (a terminal's Ctrl-C reaches only the grid, which
// forwards it once: a second signal would stop a particle run without its checkpoint), stdin
// from /dev/null, stdout and stderr appended to the log.
// With a launcher, `/bin/sh -c` runs the launched command (the group then holds the shell, or
// the launcher it became; MPI launchers put their ranks in groups of their own and forward a
// signal to them once).
pid_t spawn(const ChildTask& task) {
  std::vector<std::string> words = {"twinflow"};
  if (task.launcher.empty())
    words.insert(words.end(), task.arguments.begin(), task.arguments.end());
  else
    words = {"sh", "-c", launched_command(task.launcher, task.arguments)};
  const std::vector<char*> argv = argv_of(words);
  const ChildFiles files(task.log.c_str(), O_WRONLY | O_CREAT | O_APPEND);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
  posix_spawnattr_setpgroup(&attributes, 0);
  sigset_t defaults, mask;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  sigemptyset(&mask);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setsigmask(&attributes, &mask);
  std::vector<std::string> saved = environment_before_mpi();
  std::vector<char*> launcher_environment;
  for (auto& v : saved) launcher_environment.push_back(v.data());
  launcher_environment.push_back(nullptr);
  char** environment =
      task.launcher.empty() || saved.empty() ? environ : launcher_environment.data();
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, task.launcher.empty() ? "/proc/self/exe" : "/bin/sh",
                             files.get(), &attributes, argv.data(), environment);
  posix_spawnattr_destroy(&attributes);
  if (rc != 0)
    throw std::runtime_error("cannot start a child twinflow: " + std::string(std::strerror(rc)));
  return pid;
}

// The last "twinflow: ..." line the child wrote after `offset` (else its last line).
std::string last_message(const fs::path& log, std::uintmax_t offset) {
  std::ifstream in(log, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(offset));
  std::string line, last_line, last_error;
  while (std::getline(in, line)) {
    if (trim(line).empty()) continue;
    last_line = line;
    if (line.rfind("twinflow: ", 0) == 0) last_error = line;
  }
  std::string m = last_error.empty() ? last_line : last_error.substr(10);
  if (m.rfind("error: ", 0) == 0) m = m.substr(7);
  return m;
}

std::string timestamp() {
  const std::time_t now = std::time(nullptr);
  char text[64];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", std::localtime(&now));
  return text;
}

} // namespace

int run_children(const std::vector<ChildTask>& tasks, int jobs,
                 const std::function<void(std::size_t, const ChildResult&)>& on_done) {
  struct sigaction action {};
  struct sigaction old_int {};
  struct sigaction old_term {};
  action.sa_handler = on_grid_stop_signal;
  sigemptyset(&action.sa_mask);
  signals_received = 0;
  last_signal = 0;
  sigaction(SIGINT, &action, &old_int);
  sigaction(SIGTERM, &action, &old_term);
  struct Running {
    pid_t pid;
    std::size_t task;
    std::chrono::steady_clock::time_point start;
    std::uintmax_t log_offset;
  };
  std::vector<Running> running;
  std::size_t next = 0;
  int forwarded = 0;
  while (true) {
    while (signals_received == 0 && next < tasks.size() &&
           static_cast<int>(running.size()) < jobs) {
      const ChildTask& t = tasks[next];
      {
        std::ofstream header(t.log, std::ios::app);
        header << "# " << timestamp() << ": " << task_command(t) << "\n";
      }
      const std::uintmax_t offset = fs::file_size(t.log);
      running.push_back({spawn(t), next, std::chrono::steady_clock::now(), offset});
      ++next;
    }
    // To a launcher's group (the shell, or the launcher it became) the stop goes as SIGUSR1:
    // srun and mpirun pass it on to the ranks, which checkpoint and exit 5, while srun answers
    // SIGTERM by cancelling the step with SIGKILL (measured: Slurm 22.05, docs/cluster.md).
    for (; forwarded < signals_received; ++forwarded)
      for (const auto& r : running)
        if (tasks[r.task].launcher.empty())
          kill(r.pid, last_signal);
        else
          kill(-r.pid, SIGUSR1);
    if (running.empty() && (next == tasks.size() || signals_received > 0)) break;
    bool reaped = false;
    for (auto it = running.begin(); it != running.end();) {
      int status = 0;
      if (waitpid(it->pid, &status, WNOHANG) != it->pid) {
        ++it;
        continue;
      }
      ChildResult result;
      result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      result.wall_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - it->start).count();
      result.message = last_message(tasks[it->task].log, it->log_offset);
      result.stopped = forwarded > 0;
      if (WIFSIGNALED(status) && result.message.empty())
        result.message = "killed by signal " + std::to_string(WTERMSIG(status));
      const std::size_t task = it->task;
      it = running.erase(it);
      reaped = true;
      on_done(task, result);
    }
    if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  return signals_received > 0 ? static_cast<int>(last_signal) : 0;
}

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
  std::string s = v->is_string() ? v->get<std::string>() : trim(v->dump()); // true, false
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

int run_study(const GridOptions& o, Study& s, std::vector<Point>& points) {
  const fs::path dir =
      o.run.out.empty()
          ? fs::path("twinflow-runs") / (fs::path(o.case_file).stem().string() + "-" + s.name)
          : o.run.out;
  const fs::path json_path = dir / (s.name + ".json");
  std::vector<std::string> varied;
  for (const auto& [key, values] : s.grid.at("vary").items()) varied.push_back(key);

  // Everything is decided before the first write: a refused directory stays untouched.
  if (fs::exists(dir) && !fs::is_directory(dir))
    throw io::InputError(dir.string() + ": exists and is not a directory");
  std::map<std::string, io::Json> previous;
  std::map<std::string, std::string> previous_command; // what each point ran then
  bool afresh = o.run.force;
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
          previous[io::text(*row, {"point"})] = *row;
          previous_command[io::text(*row, {"point"})] = io::text(p, {"command"});
        }
  } else if (fs::exists(dir) && !fs::is_empty(dir) && !o.run.force) {
    throw io::InputError(dir.string() + ": exists and holds no " + s.name +
                         ".json; use --force to use it anyway or another --out");
  }
  if (afresh) // only what a grid writes
    for (const char* owned : {"points", "reference"}) fs::remove_all(dir / owned);
  fs::create_directories(dir / "points");
  if (s.prepare)
    if (const int rc = s.prepare(dir)) return rc;

  // Rows: earlier results stand, rejected points are failed, the rest runs.
  std::vector<io::Json> rows(points.size());
  std::vector<ChildTask> tasks;
  std::vector<std::size_t> task_point;
  std::vector<bool> restarted;
  std::size_t settled = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    const fs::path point_dir = dir / "points" / p.name;
    io::Json& row = rows[i];
    row["point"] = p.name;
    row["status"] = "pending";
    row["reason"] = "";
    row["exit_code"] = io::Json();
    for (std::size_t a = 0; a < varied.size(); ++a)
      row[varied[a]] = s.grid.at("vary").at(varied[a]).at(p.value_index[a]);
    for (const auto& [key, value] : p.columns.items()) row[key] = value;
    const auto prev = previous.find(p.name);
    const io::Json* previous_row = prev == previous.end() ? nullptr : &prev->second;
    row["wall_seconds"] =
        previous_row ? previous_row->value("wall_seconds", io::Json()) : io::Json();
    if (!p.rejected.empty()) {
      row["status"] = "failed";
      row["exit_code"] = 2;
      row["reason"] = p.rejected;
      ++settled;
      continue;
    }
    if (!afresh && s.finished(p, point_dir, previous_row, row)) {
      points[i].command = previous_command[p.name];
      std::cerr << s.name << ": point " << p.name
                << " skipped (finished earlier: " << io::text(row, {"status"}) << ")\n";
      ++settled;
      continue;
    }
    ChildTask t;
    t.arguments = {s.child_command, o.case_file, "--out", point_dir.string()};
    for (const auto& a : o.settings) t.arguments.insert(t.arguments.end(), {"--set", a});
    for (const auto& a : p.assignments) t.arguments.insert(t.arguments.end(), {"--set", a});
    const bool restart = fs::exists(particle_checkpoint(point_dir));
    if (restart)
      t.arguments.push_back("--restart"); // the particle stage continues from its checkpoint
    else if (has_stage_folder(point_dir))
      t.arguments.push_back("--force"); // a run cut short after its particle stage: afresh
    t.log = point_dir / "log.txt";
    t.launcher = o.launcher;
    tasks.push_back(t);
    task_point.push_back(i);
    restarted.push_back(restart);
  }
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  // A launcher places the points' processes itself (on this node or others): one at a time
  // unless --jobs says.
  int jobs = o.jobs > 0            ? o.jobs
             : !o.launcher.empty() ? 1
                                   : std::max(1, cores / std::max(1, o.run.threads));
  jobs = std::max(1, std::min<int>(jobs, static_cast<int>(tasks.size())));
  const int threads = o.run.threads > 0     ? o.run.threads
                      : jobs > 1 && !o.plan ? 1
                                            : 0; // 0: the child's default
  for (std::size_t t = 0; t < tasks.size(); ++t) {
    if (threads > 0)
      tasks[t].arguments.insert(tasks[t].arguments.end(), {"--threads", std::to_string(threads)});
    fs::create_directories(tasks[t].log.parent_path());
    points[task_point[t]].command = task_command(tasks[t]);
  }
  write_table(dir, s, o.launcher, varied, points, rows);
  if (o.plan) { // each point's command as a script, for a scheduler to run (docs/cluster.md)
    for (const Point& p :
         points) // an earlier plan's script of a point finished (or rejected) since
      fs::remove(dir / "points" / p.name / "command.sh");
    for (std::size_t t = 0; t < tasks.size(); ++t) {
      const Point& p = points[task_point[t]];
      const fs::path script = dir / "points" / p.name / "command.sh";
      io::write_file_atomically(script, "#!/bin/sh\n# " + s.name + " point " + p.name + " (" +
                                            s.name + " --plan): run it, then the same " + s.name +
                                            " command again for the table\n" +
                                            (o.launcher.empty() ? "exec " : "") + p.command + "\n");
      fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
    }
    std::cerr << s.name << ": planned " << tasks.size() << " of " << points.size()
              << " points, nothing run: DIR/points/NNN/command.sh each (DIR = " << dir.string()
              << "); the same command without --plan then skips the finished ones and writes "
                 "the table\n";
    return 0;
  }
  std::cerr << s.name << ": " << points.size() << " points, " << tasks.size() << " to run, " << jobs
            << " at a time" << (threads > 0 ? ", " + std::to_string(threads) : "")
            << (threads > 0 ? " thread(s) each" : "")
            << (o.launcher.empty() ? "" : ", each under '" + o.launcher + "'")
            << "; table: " << (dir / (s.name + ".csv")).string() << "\n";

  double wall_sum = 0;
  std::size_t done_now = 0;
  const int signal = run_children(tasks, jobs, [&](std::size_t t, const ChildResult& result) {
    const std::size_t i = task_point[t];
    io::Json& row = rows[i];
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
    const double earlier = restarted[t] && std::isfinite(before) ? before : 0;
    row["wall_seconds"] = earlier + result.wall_seconds;
    write_table(dir, s, o.launcher, varied, points, rows);
    wall_sum += result.wall_seconds;
    ++done_now;
    ++settled;
    const double eta = wall_sum / done_now * static_cast<double>(tasks.size() - done_now) / jobs;
    std::cerr << s.name << ": point " << settled << "/" << points.size() << " done ("
              << io::text(row, {"status"}) << "), ETA "
              << (done_now == tasks.size() ? "0s" : duration_text(eta)) << "\n";
  });
  std::map<std::string, int> counts;
  for (const auto& row : rows) ++counts[io::text(row, {"status"})];
  std::cerr << s.name << ":";
  for (const auto& [status, n] : counts) std::cerr << " " << n << " " << status;
  std::cerr << "; table: " << (dir / (s.name + ".csv")).string() << "\n";
  if (signal) {
    std::cerr << s.name << ": interrupted by a signal; run the same command again to continue\n";
    return kExitInterrupted;
  }
  write_report(dir);
  return 0;
}

} // namespace twinflow::study
