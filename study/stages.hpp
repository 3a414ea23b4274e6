#pragma once
// The stages of a paired run, each into its folder of the run directory: particle, transport,
// continuum (nominal; calibrated), compare; and `run`, which chains them. Each takes the case as
// resolved once at the edge; bad input throws io::InputError (exit 2), and nothing is written
// before every input is checked.

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "io/files.hpp"
#include "study/case.hpp"

namespace twinflow::study {

// The particle stage's checkpoint in a run directory (what --restart continues from).
inline std::filesystem::path particle_checkpoint(const std::filesystem::path& run_dir) {
  return run_dir / "particle" / "checkpoint.twfc";
}

// RUNDIR/particle (Particle/Ensemble > 1: its realisations, merged; study/ensemble.hpp). Exit
// code: 0, 4 (the run went unstable), 5 (interrupted, checkpoint written).
int particle_stage(const Case& c, const RunOptions& options);
// One particle run into `stage`'s folder, its checkpoint at `checkpoint` (restart: continued
// from it); every rank takes part, rank 0 writes.
int particle_run(const Case& c, const RunOptions& options, const io::StageDirectory& stage,
                 const std::filesystem::path& checkpoint, bool restart);
// `twinflow particle`: the stage, its inputs recorded as `run` records them (a later `run` of
// the same case reuses the results).
int particle_command(const Case& c, const RunOptions& options);

// RUNDIR/transport: the fluid's coefficients at the state point; bulk measurements are cached
// across run directories under the hash of their inputs ($TWINFLOW_CACHE).
int transport_stage(const Case& c, const RunOptions& options);

// RUNDIR/<stage_name>: the continuum twin of the case's Continuum section, its coefficients
// from RUNDIR/transport where the case says so.
int continuum_stage(const Case& c, const RunOptions& options,
                    const std::string& stage_name = "continuum");
// `twinflow continuum`: the stage, then the case it ran as RUNDIR/case.json (what `twinflow
// compare RUNDIR` compares).
int continuum_command(const Case& c, const RunOptions& options);

// Thrown by calibrated_case when the particle run's wall measurements make parameters the twin
// refuses; `run` then goes on without the calibrated twin.
struct NoCalibratedTwin : io::InputError {
  using io::InputError::InputError;
};

// The calibrated twin's case: the nominal one with the walls calibrated from the particle run
// in `run_dir` (compare/calibration.hpp), its values recorded.
Case calibrated_case(const Case& nominal, const std::filesystem::path& run_dir);

// RUNDIR/compare and RUNDIR/report; `c`: the case the twins ran (RUNDIR/case.json with
// `twinflow compare RUNDIR`).
int compare_stage(const Case& c, const std::filesystem::path& run_dir);

// Figures and report.md/html in DIR/report (a run, a sweep or a stability map), by the Python
// package compare/report/; a missing python3 with matplotlib is said, not an error.
void write_report(const std::filesystem::path& dir);

// A number as a record or a console line states it: `digits` significant digits (%g).
inline std::string number_text(double v, int digits = 6) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, v);
  return text;
}

// A number as a record keeps it exactly: the shortest text that reads back to the same double.
inline std::string exact_text(double v) {
  char text[40];
  const auto end = std::to_chars(text, text + sizeof text, v).ptr;
  return std::string(text, end);
}

// Whether the user's assignments (--set, a grid's --vary) choose Continuum/Coefficients/Source;
// if not, `run` feeds the twin the transport stage's coefficients.
bool chooses_coefficient_source(const std::vector<std::string>& assignments);

// All stages; a stage whose inputs are unchanged is reused.
int run_all(Case c, const RunOptions& options);

} // namespace twinflow::study
