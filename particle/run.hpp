#pragma once
// A whole particle run: equilibration, sampling, diagnostics. The case's physics choices are
// resolved here, once, into one of the compiled model combinations.

#include <functional>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/field_file.hpp"
#include "io/json.hpp"
#include "particle/parameters.hpp"
#include "statistics/blocking.hpp"

namespace twinflow::particle {

// Mean and block standard error of a time series (statistics/blocking.hpp), as callers of the
// particle run have always named them.
using statistics::block_average;
using statistics::blocking_errors;
using statistics::Estimate;

struct RunOutput {
  io::Json summary;             // the particle stage's results
  std::string thermo_csv;       // time series, one row per sample
  std::string histograms_csv;   // velocity components and internal energies
  std::string rdf_csv;          // g(r)
  std::string correlations_csv; // VACF and MSD
  std::string fields_csv;       // binned fields on the scene's bins, with block errors
  std::string blocks_csv;       // T_kinetic of each block on those bins
  std::string wall_layers_csv;  // walled scenes: density and velocity in slices along each wall
  std::string slab_profile_csv; // heat-slab scenes: the profile along the slab direction
  std::string relaxation_csv;   // thermal relaxation scenes: the mode amplitude over time
  io::Grid field_grid;          // the scene's bins
  std::vector<io::Snapshot> field_snapshots; // cumulative averages at a sequence of times
  bool interrupted = false; // stopped early: a checkpoint was written, the rest is empty
  long steps_done = 0;
};

struct RunControl {
  // A progress line with ETA on stderr: rewritten in place every 2 s on a terminal; one line a
  // minute into a log file (stderr redirected), so that a long run's log shows where it stands.
  enum class Progress { none, terminal, log };
  Progress progress = Progress::none;
  std::string progress_label; // before "step ..." (a run inside another stage says which)
  static Progress progress_for_stderr(); // terminal or log, by isatty(stderr)
  // Polled after every step; true: write a checkpoint and return (RunOutput::interrupted).
  std::function<bool()> stop_requested;
  std::function<void(const io::Checkpoint&)> write_checkpoint;
  double checkpoint_every_seconds = 0;    // also write one this often (wall clock; 0: never)
  const io::Checkpoint* resume = nullptr; // continue from this checkpoint (bitwise)
};

RunOutput run_particles(const ParticleParameters& p, const RunControl& control = {});

struct BenchResult {
  long particles = 0;
  double seconds = 0, particle_steps_per_second = 0, bytes_per_particle = 0;
  double steps_per_list = 0;   // timed steps per pair-list build
  int ranks = 1;               // MPI ranks (the slowest rank's time counts)
  double ghosts_per_owned = 0; // ghost-plane copies per owned particle (the most on any rank)
};
// Times `steps` steps after set-up (set-up excluded). Collective on several MPI ranks.
BenchResult bench_particles(const ParticleParameters& p, long steps);

} // namespace twinflow::particle
