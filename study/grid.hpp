#pragma once
// The grid behind `twinflow sweep` and `twinflow stability`: its points (the Cartesian product
// of the --vary lists), each run as a child process of this binary (a crash or a blow-up of one
// point cannot stop the others), the table written after every finished point, and resuming an
// interrupted grid from that table and the points' own files.

#include <csignal>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "io/json.hpp"
#include "study/case.hpp"

namespace twinflow::study {

// What the grid is asked for (the command line of sweep and stability).
struct GridOptions {
  std::string case_file;
  std::vector<std::string> settings; // the user's --set
  std::vector<std::string> vary;     // "Section/Key=V1,V2,..." per option
  std::vector<double> rayleigh;      // target Rayleigh numbers (sweep)
  // out (empty: twinflow-runs/<case file stem>-<command>), force, and threads per point (0: 1
  // when points run side by side, else the child's default)
  RunOptions run;
  int jobs = 0; // points run at once; 0: cores / threads per point (1 with a launcher)
  // A command template each point runs under, e.g. "mpirun -np 2 {cmd}" or "srun -n 4 {cmd}":
  // {cmd} becomes the point's shell-quoted command (empty: the point runs directly).
  std::string launcher;
  // Write each point's command as DIR/points/NNN/command.sh (and the table, every point
  // pending) and run nothing: a scheduler's job array runs them (docs/cluster.md).
  bool plan = false;
};

// A word as a POSIX shell reads it back: bare if it has only safe characters, else in single
// quotes ('\'' for a quote inside).
std::string shell_quoted(const std::string& word);

// Checks a --launcher template before anything runs: exactly one {cmd}, one line, valid shell
// syntax, and its first word (the launcher) found on PATH when it is a program. Throws
// io::InputError naming the problem.
void check_launcher(const std::string& launcher);

// The shell command a point runs: the launcher template with {cmd} replaced by `command`'s
// words, shell-quoted (the first word is this binary's absolute path). A template that starts
// with a program gets `exec ` so that the shell becomes the launcher (signals reach it).
std::string launched_command(const std::string& launcher, const std::vector<std::string>& command);

// The case file as the grid needs it (case_reader() of study/case_file/ provides it): `check` reads
// it with extra assignments and throws io::InputError for an unknown key or a value outside its
// pattern; `load` also resolves it (values that do not fit together throw io::InputError too).
struct CaseReader {
  std::function<void(const std::vector<std::string>& settings)> check;
  std::function<Case(const std::vector<std::string>& settings)> load;
  std::function<io::Json(const std::vector<std::string>& settings)> record; // read, not resolved
};

// One --vary option: a case key and the values it takes, in the order given.
struct Axis {
  std::string key;                 // "Particle/Time step"
  std::vector<std::string> shown;  // as the user wrote them ("0 -0.01"): the table's cells
  std::vector<std::string> values; // as the case takes them ("0, -0.01"): the child's --set
};

// Parses every --vary text and checks each value against the case (with the user's --set):
// an unknown key, a value outside its key's pattern or a key given twice throws io::InputError.
std::vector<Axis> parse_axes(const GridOptions&, const CaseReader&);

// The grid as its table's JSON records it: the case file, its resolved parameters, the axes.
io::Json grid_description(const GridOptions&, const CaseReader&, const std::vector<Axis>&);

struct Point {
  std::string name;                      // "007": its run directory DIR/points/007
  std::vector<std::size_t> value_index;  // per axis
  std::vector<std::string> assignments;  // "Key=value", --set after the user's own
  std::string rejected;                  // non-empty: the case's message for these values together
  std::string command;                   // the shell command it last ran (the table records it)
  CaseParameters resolved;               // the point's parameters (when not rejected)
  io::Json columns = io::Json::object(); // the command's own columns before wall_seconds
};

// The Cartesian product of the axes (the first axis varies slowest), each point loaded through
// the CaseReader with the user's --set and its own values. `copies` > 1 repeats every combination
// (sweep --rayleigh: one copy per target). Points the case rejects as a whole (e.g. walls with
// ec-verlet) are kept with their message; if every point is rejected, throws io::InputError.
std::vector<Point> make_points(const GridOptions&, const CaseReader&, const std::vector<Axis>&,
                               std::size_t copies = 1);

// How a child process ended.
struct ChildResult {
  int exit_code = 0;       // the child's exit code; 128 + N when signal N killed it
  double wall_seconds = 0; // of this attempt
  std::string message;     // its last "twinflow: ..." line (or last line), without the prefix
  bool stopped = false;    // the grid forwarded a stop signal (Ctrl-C, SIGTERM) to it
};

// A child stopped by a signal: with a checkpoint (exit 5), or killed by one of the stop signals
// outside its particle stage (128 + N).
inline bool interrupted_exit(int exit_code) {
  return exit_code == kExitInterrupted || exit_code == 128 + SIGINT || exit_code == 128 + SIGTERM ||
         exit_code == 128 + SIGUSR1;
}

// Runs `twinflow ARGUMENTS` (this very binary) with stdout and stderr appended to `log`; with a
// launcher, `/bin/sh -c` runs launched_command(launcher, ...) instead.
struct ChildTask {
  std::vector<std::string> arguments;
  std::filesystem::path log;
  std::string launcher; // a --launcher template; empty: none
};

// Keeps a copy of the environment as the program started, before MPI_Init: a launcher gets it
// (the singleton MPI_Init of this process adds OMPI_*/PMIX_* variables with which a child
// `mpirun` fails at once). Without the call launchers get the current environment.
void save_environment_before_mpi();

// What a task runs, as one shell command line (its log's header, the table's "command").
std::string task_command(const ChildTask&);

// Runs the tasks, up to `jobs` at once, and calls `on_done` (in this thread) as each ends. On
// SIGINT/SIGTERM no new task starts and the signal is forwarded to the running ones (as SIGUSR1
// to a launcher), which are waited for. Returns the signal received (0: none).
int run_children(const std::vector<ChildTask>& tasks, int jobs,
                 const std::function<void(std::size_t task, const ChildResult&)>& on_done);

// What one command (sweep or stability) adds to the shared driver.
struct Study {
  std::string name;          // "sweep" or "stability": DIR/<name>.csv, DIR/<name>.json
  std::string child_command; // the stage each point runs: "run" or "particle"
  std::vector<std::string> columns_before_wall; // e.g. target_rayleigh, gravity
  std::vector<std::string> columns_after_wall;  // fixed columns; other keys follow, sorted
  io::Json grid; // what makes two invocations the same grid (compared on resume)
  // Runs once the directory is accepted and before any point (e.g. the reference transport
  // run); returns an exit code, 0 to go on.
  std::function<int(const std::filesystem::path& dir)> prepare;
  // True when the point's earlier result stands and it is not run again; may fill the row.
  std::function<bool(const Point&, const std::filesystem::path& point_dir,
                     const io::Json* previous_row, io::Json& row)>
      finished;
  // Fills status, reason and the command's columns from a child that ended.
  std::function<void(const Point&, const std::filesystem::path& point_dir, const ChildResult&,
                     io::Json& row)>
      describe;
};

// The shared driver: refuses a different grid in DIR (exit 2) unless --force, runs the points
// not finished yet (continuing interrupted particle runs with --restart), writes the table
// after every point, prints a progress line per point. Exit code: 0, or 5 when interrupted.
int run_study(const GridOptions&, Study&, std::vector<Point>& points);

// Helpers for the commands' columns.
io::Json number_or_null(double v);

} // namespace twinflow::study
