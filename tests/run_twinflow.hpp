#pragma once
// Runs the twinflow binary from a test: exit code and combined output.

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/wait.h>

namespace twinflow::testing {

struct Result {
  int code;
  std::string output;
};

// A shell command as given (e.g. the hint an interrupted run prints): exit code and combined
// output.
inline Result run_command(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  std::string out;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), pipe)) out += buf.data();
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// The transport cache is off unless a test names one (tests measure, they do not reuse). env:
// a prefix for the binary, e.g. "env -u GOMP_SPINCOUNT".
inline Result run_twinflow(const std::string& args, const std::string& cache = "off",
                           const std::string& env = "") {
  return run_command("TWINFLOW_CACHE='" + cache + "' " + env + " " + std::string(TWINFLOW_BINARY) +
                     " " + args);
}

// An empty path under the temporary directory, unique per test and name.
inline std::filesystem::path fresh_dir(const std::string& test, const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("twinflow_" + test + "_" + name);
  std::filesystem::remove_all(d);
  return d;
}

} // namespace twinflow::testing
