#include "transport/jobs.hpp"

#include <omp.h>

#include <algorithm>
#include <exception>
#include <numeric>

#include "particle/decomposition.hpp"

namespace twinflow::transport {

void run_jobs(std::vector<Job> jobs) {
  const int threads = omp_get_max_threads();
  if (particle::Slabs::world_size() > 1 || threads == 1 || jobs.size() < 2) {
    for (Job& job : jobs) job.work();
    return;
  }
  std::vector<std::size_t> order(jobs.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return jobs[a].cost > jobs[b].cost; });
  std::vector<std::exception_ptr> errors(jobs.size());
  const int n = static_cast<int>(jobs.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::min(threads, n))
  for (int k = 0; k < n; ++k) {
    omp_set_num_threads(1); // this thread's runs: one thread each (nested regions are inactive)
    try {
      jobs[order[k]].work();
    } catch (...) {
      errors[order[k]] = std::current_exception();
    }
  }
  omp_set_num_threads(threads);
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

} // namespace twinflow::transport
