#include "study/grid.hpp"

#include <algorithm>
#include <chrono>
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

extern char** environ;

// The grid's children: launcher templates checked and filled, each point this binary again in its
// own process group (or under a launcher), signals forwarded once, at most `jobs` at a time.
namespace twinflow::study {

namespace fs = std::filesystem;

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
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue; // blank
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

// SIGINT and SIGTERM counted while the children run (on_grid_stop_signal); the handlers before
// are back when it goes.
class StopSignals {
public:
  StopSignals() {
    signals_received = 0;
    last_signal = 0;
    struct sigaction action {};
    action.sa_handler = on_grid_stop_signal;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
  }
  ~StopSignals() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

struct Running {
  pid_t pid;
  std::size_t task;
  std::chrono::steady_clock::time_point start;
  std::uintmax_t log_offset; // where this run's lines begin in the task's log
};

// Starts task `index`, its log first given a line with the time and the command.
Running start_child(const ChildTask& t, std::size_t index) {
  {
    std::ofstream header(t.log, std::ios::app);
    header << "# " << timestamp() << ": " << task_command(t) << "\n";
  }
  const std::uintmax_t offset = fs::file_size(t.log);
  return {spawn(t), index, std::chrono::steady_clock::now(), offset};
}

// Passes the stops received since the last call on to the running children. To a launcher's
// group (the shell, or the launcher it became) a stop goes as SIGUSR1: srun and mpirun pass it on
// to the ranks, which checkpoint and exit 5, while srun answers SIGTERM by cancelling the step
// with SIGKILL (measured: Slurm 22.05, docs/cluster.md).
void forward_stops(const std::vector<ChildTask>& tasks, const std::vector<Running>& running,
                   int& forwarded) {
  for (; forwarded < signals_received; ++forwarded)
    for (const auto& r : running)
      if (tasks[r.task].launcher.empty())
        kill(r.pid, last_signal);
      else
        kill(-r.pid, SIGUSR1);
}

// Reaps the children that have finished, on_done for each; whether any had.
bool reap_finished(const std::vector<ChildTask>& tasks, std::vector<Running>& running, bool stopped,
                   const std::function<void(std::size_t, const ChildResult&)>& on_done) {
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
    result.stopped = stopped;
    if (WIFSIGNALED(status) && result.message.empty())
      result.message = "killed by signal " + std::to_string(WTERMSIG(status));
    const std::size_t task = it->task;
    it = running.erase(it);
    reaped = true;
    on_done(task, result);
  }
  return reaped;
}

} // namespace

int run_children(const std::vector<ChildTask>& tasks, int jobs,
                 const std::function<void(std::size_t, const ChildResult&)>& on_done) {
  const StopSignals stop_signals;
  std::vector<Running> running;
  std::size_t next = 0;
  int forwarded = 0;
  while (true) {
    for (; signals_received == 0 && next < tasks.size() && static_cast<int>(running.size()) < jobs;
         ++next)
      running.push_back(start_child(tasks[next], next));
    forward_stops(tasks, running, forwarded);
    if (running.empty() && (next == tasks.size() || signals_received > 0)) break;
    if (!reap_finished(tasks, running, forwarded > 0, on_done))
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return signals_received > 0 ? static_cast<int>(last_signal) : 0;
}

} // namespace twinflow::study
