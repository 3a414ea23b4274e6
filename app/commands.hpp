#pragma once
// The twinflow commands as the command line gives them: each maps its options and the case
// file onto the libraries' structs (once) and calls the study. Bad input throws io::InputError.

#include <string>
#include <vector>

#include "study/case.hpp"

namespace twinflow::app {

struct CommandLine {
  std::string command;
  std::string target;                // CASE file or RUNDIR
  std::vector<std::string> settings; // --set 'Section/Key=value', in order
  study::RunOptions run;             // --out, --force, --restart, --wall-time, --threads
  // sweep and stability
  std::vector<std::string> vary; // "Section/Key=V1,V2,..." per option
  std::vector<double> rayleigh;  // target Rayleigh numbers (sweep)
  int jobs = 0;                  // points run at once; 0: cores / threads per point
  std::string launcher;          // each point under this template ("mpirun -np 2 {cmd}")
  bool plan = false;             // write each point's command.sh, run nothing
};

struct Command {
  const char* name;
  const char* arguments; // "CASE", "RUNDIR" or ""
  const char* help;
  int (*run)(const CommandLine&);
  // `twinflow COMMAND --help`: its options, an example, what it writes, its exit codes.
  const char* details;
};
const std::vector<Command>& commands();

} // namespace twinflow::app
