#pragma once
// The compare stage: the particle run against each continuum twin on the scene's bins (fields
// with error bars, Nusselt numbers, wall temperature jumps, mid-line profiles, error against run
// time). Reads the stages' files, computes, returns what to write; no solver.

#include <array>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "compare/calibration.hpp"
#include "compare/parameters.hpp"
#include "compare/twin_distance.hpp"
#include "io/field_file.hpp"
#include "io/json.hpp"
#include "scene/scene.hpp"

namespace twinflow::compare {

// What compare needs of a finished particle run (RUNDIR/particle).
struct ParticleRecord {
  io::Json summary;
  io::FieldFile::Contents fields;
  std::vector<std::vector<double>> temperature_blocks; // blocks.csv (runs before it: empty)
  std::array<bool, 3> walled{{false, false, false}};
  // The final averages, with the per-block temperatures behind them.
  BinnedState final_state() const;
};
// Throws io::InputError (with what to run) when the stage has not finished or binned nothing.
ParticleRecord read_particle_record(const std::filesystem::path& run_dir,
                                    const scene::SceneParameters& scene);

// A finished continuum twin (RUNDIR/continuum, RUNDIR/continuum_calibrated).
struct TwinRecord {
  std::string name; // "nominal", "calibrated"
  std::string stage;
  io::Json summary;
  BinnedState state;
};
// The twins that have run, nominal first; throws io::InputError without a nominal twin.
std::vector<TwinRecord> read_twins(const std::filesystem::path& run_dir, const io::Grid& grid);

struct Comparison {
  io::Json metrics;
  std::string bins_csv, profiles_csv, error_vs_time_csv;
  std::ostringstream log; // the console's summary lines
};

Comparison compare_twins(const ParticleRecord& run, const std::vector<TwinRecord>& twins,
                         const scene::SceneParameters& scene, const CompareParameters& compare,
                         const TwinFacts& twin, const std::string& case_name);

} // namespace twinflow::compare
