#pragma once
// Ensembles (Particle/Ensemble = K, `--ensemble K`): K independent realisations of the particle
// run (seeds Seed, Seed+1, ...), one after another, each into RUNDIR/particle/realisations/NN/,
// merged into RUNDIR/particle/ in the files of one run, so that compare and the report read them
// unchanged. The merge goes by the names the particle stage gives its numbers: a value X with
// an error X_stderr (summary.json) or a column X with X_se (the CSV tables, the field file's
// FIELD_stderr) becomes the realisations' mean with the larger of two errors, that of the
// spread, sd / sqrt(K), and that of the blocks within each, sqrt(sum e_k^2) / K.

#include <filesystem>
#include <string>
#include <vector>

#include "io/field_file.hpp"
#include "io/json.hpp"
#include "statistics/blocking.hpp"

namespace twinflow::study {

struct Case;
struct RunOptions;

// The mean of K independent estimates and its error: the larger of the spread's and the
// errors' own (either alone can be short: the spread has K - 1 degrees of freedom, the blocks
// can be shorter than the slowest mode).
statistics::Estimate ensemble_mean(const std::vector<double>& values,
                                   const std::vector<double>& errors);

// summary.json "results" of the realisations merged: X with X_stderr as ensemble_mean; other
// errors (X_stderr_fit, X_stderr_blocking, ...) as sqrt(sum e^2) / K; wall_seconds summed,
// *_max the largest; other numbers that differ the mean; everything else as the first holds it.
io::Json merge_results(const std::vector<io::Json>& results);

// A CSV table of each realisation (the same rows and columns) merged: a column X beside X_se as
// ensemble_mean, a column equal in all (coordinates, names, steps) kept, other numbers the mean.
std::string merge_table(const std::vector<std::string>& tables, const std::string& name);

// blocks.csv (block,bin,T_kinetic) of each realisation, one after another: realisation k's
// blocks numbered after k - 1's, so that blocks merged in 2s and 4s stay within one realisation.
std::string concatenate_blocks(const std::vector<std::string>& tables, const std::string& name);

// The field files' snapshots merged one by one (the same times): fields as ensemble_mean, the
// wall time and particle steps summed (what the ensemble cost up to that time).
std::vector<io::Snapshot> merge_snapshots(const std::vector<io::FieldFile::Contents>& files);

// The particle stage for Particle/Ensemble > 1 (every rank; rank 0 merges and writes). With
// --restart, realisations already done are kept and the interrupted one continues.
int ensemble_particle_stage(const Case& c, const RunOptions& options);

} // namespace twinflow::study
