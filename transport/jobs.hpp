#pragma once
// Independent particle runs of one measurement spread over the cores. On one MPI process with T
// OpenMP threads up to T jobs run at once, each single-threaded (a run's results do not depend on
// its threads: docs/architecture.md, "Design decisions"), the costliest first so that the long runs
// do not end last; under mpirun one after another, since every run is collective over the
// ranks. Each job writes only its own result: the outcome is the same whatever the spread.

#include <functional>
#include <vector>

namespace twinflow::transport {

struct Job {
  double cost = 1; // any unit: only the order of the jobs depends on it
  std::function<void()> work;
};

// Runs every job; an exception in one is rethrown (the first in job order) once all have ended.
void run_jobs(std::vector<Job> jobs);

} // namespace twinflow::transport
