#pragma once
// The twinflow subcommands. Each takes the parsed command line; bad input throws io::InputError.

#include <filesystem>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/json.hpp"

namespace twinflow::app {

struct SceneParameters;

struct CommandLine {
  std::string command;
  std::string target; // CASE file or RUNDIR
  std::string out;    // run directory ("" = twinflow-runs/<case name>)
  std::vector<std::string> overrides;
  int threads = 0; // 0: OpenMP's default
  bool force = false;
  bool restart = false;
  double wall_time_limit = 0; // seconds; 0: none. Past it a run checkpoints and stops.
  // sweep and stability
  std::vector<std::string> vary; // "Section/Key=V1,V2,..." per option
  std::vector<double> rayleigh;  // target Rayleigh numbers (sweep)
  int jobs = 0;                  // points run at once; 0: cores / threads per point
};

// Shared by the stages (app/compare_stage.cpp): a wall's name in the particle summary
// ("x_lower", ...), a wall's heat-flux error in that summary (the largest over its blockings, 1,
// 2 and 4 blocks merged; runs before the blockings were recorded: the 20-block one), and the
// scene's heated direction (the walled direction whose two thermal walls differ in temperature;
// -1: none).
std::string wall_name(int d, int side);
double largest_stderr(const io::Json& results, const std::string& wall);
int heated_direction(const SceneParameters& s);

// Exit code of a run stopped by a signal or the wall-time limit after writing its checkpoint.
constexpr int kExitInterrupted = 5;

// Thrown by stages that a later issue fills in; exit code 3.
struct NotImplemented : std::runtime_error {
  using std::runtime_error::runtime_error;
};

int check_case(const CommandLine&);
int print_parameters(const CommandLine&);
int particle_stage(const CommandLine&);
// `twinflow particle`: particle_stage, and its inputs recorded for `run` to reuse.
int particle_command(const CommandLine&);
int continuum_stage(const CommandLine&);
// The continuum twin into RUNDIR/<stage_name> ("continuum", "continuum_calibrated").
int continuum_twin(const CommandLine&, const std::string& stage_name);
int compare_stage(const CommandLine&);
// RUNDIR/report (or a sweep's / stability map's): figures and report.md/html.
void write_report(const std::filesystem::path& dir);
// --set options that make the calibrated twin of a finished particle run in run_dir.
// `overrides`: the command's --set options (its Transport/, Continuum/, Compare/ keys count).
std::vector<std::string> calibrated_twin_overrides(const std::string& run_dir,
                                                   const std::vector<std::string>& overrides);
int transport_stage(const CommandLine&);
// The transport measurement's version: part of its cache key and of its stage inputs in `run`,
// bumped when a measurement changes (results of an older method are not reused).
constexpr int kTransportMethod = 4; // 3: relaxation fit window from the noise (decay_fit.hpp);
                                    // 4: the wall run's slope and flux errors from the blockings
int bench(const CommandLine&);
int run_all(const CommandLine&);
int sweep(const CommandLine&);
int stability(const CommandLine&);

} // namespace twinflow::app
