#pragma once
// `run` and `transport` under mpirun: every rank takes part in the particle runs (the solver
// splits each over MPI_COMM_WORLD), rank 0 alone runs the serial stages, reads and writes every
// file and prints; the other ranks wait for it and end with its exit code. On one process (no
// launcher, or -np 1) every helper here just runs its work.

#include <exception>
#include <functional>
#include <string>

#include "io/json.hpp"

namespace twinflow::study {

// MPI_COMM_WORLD's size (1 without MPI), as the code running sees it: inside rank_zero_runs'
// work it is 1 (rank 0 is alone there; the helpers below then just run their work).
int rank_count();
bool on_rank_zero(); // true on one process
// True inside rank_zero_runs' work on several ranks: a stage there uses MPI_COMM_SELF (the
// continuum twin), as the other ranks are not listening.
bool rank_zero_alone();

// Rank 0 runs `work`; every rank returns its exit code. An exception on rank 0 is rethrown there
// (main prints it) once the others have its exit code (exit_code_of), which they return.
int rank_zero_runs(const std::function<int()>& work);

// Every rank runs `work` (collective inside: a particle run); all return one exit code: rank 0's
// if not 0, else the largest of the others'. An exception is rethrown on the rank it came from
// (on rank 0 if it threw there too, so that one rank prints it).
int every_rank_runs(const std::function<int()>& work);

// Rank 0's `text` on every rank (a decision only rank 0 can take: a file it read).
std::string from_rank_zero(const std::string& text);
double from_rank_zero(double value);

// How a stage ran, for its summary.json ("execution"): MPI ranks, OpenMP threads per rank and
// the particle decomposition ("1 rank" or "R slabs along <axis>").
io::Json execution_record(int dimension);
// "R ranks x T threads", the first console line of a multi-rank run.
std::string ranks_and_threads();

// The exit code main gives an exception (docs/usage.md, "Exit codes").
int exit_code_of(const std::exception_ptr& error);

} // namespace twinflow::study
