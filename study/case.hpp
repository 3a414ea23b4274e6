#pragma once
// A paired case as the study runs it: every stage's parameters, resolved once from the case
// file (study/case_file/), and the record of every key's value that stages write as provenance and
// hash as their inputs.

#include <filesystem>
#include <string>
#include <vector>

#include "compare/parameters.hpp"
#include "continuum/parameters.hpp"
#include "io/json.hpp"
#include "particle/parameters.hpp"
#include "scene/scene.hpp"
#include "transport/parameters.hpp"

namespace twinflow::study {

// Bounds of the stability map (twinflow stability).
struct StabilityBounds {
  double energy_drift = 1e-3;          // largest acceptable max |dE/E|
  double temperature_tolerance = 0.05; // |T / T_target - 1|
  double fluctuation_number = 1.0;     // 000:(3.34)'s number must stay below this
};

// Which twin runs and where its coefficients come from.
struct TwinChoice {
  bool coefficients_from_transport = false; // RUNDIR/transport/summary.json, else the case's
  bool model_chosen_automatically = false;  // Continuum/Model = auto
  bool kinetic_slip_automatically = false;  // Continuum/Wall slip = auto, no Slip lengths
  bool wall_jumps_automatically = false;    // Continuum/Wall jump = auto, no Kapitza given
  bool wall_jumps_from_theory = false;      // the twin's thermal walls from the wall layer
  bool wall_slips_from_theory = false;      // its no-slip walls' slip from the slip layer
  double low_mach_threshold = 0.2;          // its threshold on the walls' epsilon
  double compressible_threshold = 0.1;      // its threshold on the stratification g H / c^2
};

struct CaseParameters {
  std::string name;
  scene::SceneParameters scene;
  particle::ParticleParameters particle;
  transport::TransportParameters transport;
  continuum::ContinuumParameters continuum;
  TwinChoice twin;
  double checkpoint_interval_minutes = 10; // Particle/Checkpoint interval; 0: when stopped only
  int ensemble = 1; // Particle/Ensemble: independent realisations, merged (study/ensemble.hpp)
  compare::CompareParameters compare;
  StabilityBounds stability;
};

struct Case {
  CaseParameters parameters;
  io::Json record = io::Json::object();   // "Section/Key" -> the value's text, every key
  io::Json defaults = io::Json::object(); // "Section/Key" -> its declared default text
  std::string file;                       // the case file as given
  std::vector<std::string> settings;      // the user's --set assignments, in order
  // A value a stage hands a later one, recorded as the case file would hold it.
  void record_value(const std::string& path, const std::string& text) { record[path] = text; }
};

// How a command runs (the command line's options, nothing of the case).
struct RunOptions {
  std::filesystem::path out;  // run directory; empty: twinflow-runs/<case name>
  bool force = false;         // overwrite an earlier run's results
  bool restart = false;       // continue an interrupted particle run from its checkpoint
  double wall_time_limit = 0; // seconds; 0: none. Past it a particle run checkpoints and stops
  int threads = 0;            // OpenMP threads; 0: the runtime's default
  // The command as typed, shell-quoted, with --restart: what an interrupted run tells the user
  // to run to continue it. Empty: the stage composes a shorter one.
  std::string continue_command;
};

// Case keys that change no result (how often a run checkpoints): left out of every inputs hash,
// transport cache key and checkpoint comparison, so that changing them reuses and restarts.
bool changes_no_result(const std::string& path);
// The record without them: what a checkpoint or a finished run belongs to.
io::Json without_keys_that_change_no_result(io::Json record);

std::filesystem::path run_directory(const RunOptions& options, const std::string& case_name);

// Exit codes shared by the commands.
constexpr int kExitDone = 0, kExitFailed = 1, kExitBadInput = 2, kExitNotImplemented = 3,
              kExitUnstable = 4, kExitInterrupted = 5, kExitOutputFailed = 6;

} // namespace twinflow::study
