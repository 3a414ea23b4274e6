// Same seed, same result: bitwise for 1 and 2 threads, and whatever the storage order.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "helpers.hpp"
#include "particle/simulation.hpp"

using namespace twinflow::particle;
using namespace twinflow::particle::testing;

namespace {
using M = Seed002Model;

// Positions, velocities and energies indexed by particle id.
std::vector<double> snapshot(const State<3>& s) {
  std::vector<double> out(s.size() * 7);
  for (std::size_t i = 0; i < s.size(); ++i) {
    double* o = &out[s.id[i] * 7];
    for (int d = 0; d < 3; ++d) o[d] = s.x[d][i], o[3 + d] = s.v[d][i];
    o[6] = s.u[i];
  }
  return out;
}

std::vector<double> run(Integrator integrator, int threads, bool shuffle) {
  omp_set_num_threads(threads);
  auto p = seed002(integrator, 0.01);
  p.box = {{9, 9, 6}};
  Simulation<M> sim(seed002_model(p), p);
  if (shuffle) { // scramble the storage order; the sort must restore the canonical one
    auto& s = sim.state();
    std::vector<std::size_t> perm(s.size());
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), std::mt19937(7));
    auto apply = [&](auto& a) {
      auto copy = a;
      for (std::size_t k = 0; k < perm.size(); ++k) a[k] = copy[perm[k]];
    };
    for (int d = 0; d < 3; ++d) apply(s.x[d]), apply(s.v[d]);
    apply(s.u), apply(s.id);
    sim.resort();
    sim.prepare();
  }
  for (int k = 0; k < 200; ++k) sim.step();
  omp_set_num_threads(omp_get_num_procs());
  return snapshot(sim.state());
}
} // namespace

TEST(Determinism, BitwiseForOneAndTwoThreadsAndAnyStorageOrder) {
  for (const auto integrator : {Integrator::EcVerlet, Integrator::Shardlow, Integrator::Euler}) {
    const auto one = run(integrator, 1, false);
    EXPECT_TRUE(one == run(integrator, 2, false)) << to_string(integrator) << ": threads";
    EXPECT_TRUE(one == run(integrator, 2, true)) << to_string(integrator) << ": storage order";
  }
}
