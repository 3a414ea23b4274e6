// Same seed, same result: bitwise for 1 to 4 threads, and whatever the storage order.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <numeric>
#include <random>

#include <Random123/philox.h>

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
  p.box = {{9, 9, 12}}; // 10 planes of cells: 5 even units, split unevenly by 3 and 4 threads
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

TEST(Determinism, BitwiseForOneToFourThreadsAndAnyStorageOrder) {
  for (const auto integrator : {Integrator::EcVerlet, Integrator::Shardlow, Integrator::Euler}) {
    const auto one = run(integrator, 1, false);
    for (const int threads : {2, 3, 4})
      EXPECT_TRUE(one == run(integrator, threads, false))
          << to_string(integrator) << ": " << threads << " threads";
    EXPECT_TRUE(one == run(integrator, 2, true)) << to_string(integrator) << ": storage order";
  }
}

// Moments 1..4 (m[1..4]) and the largest |value| of xi and zeta over 2^21 pairs of ids, checking
// xi_ij = xi_ji and zeta_ij = -zeta_ji on the way.
namespace {
struct NoiseMoments {
  double m[5] = {0, 0, 0, 0, 0}, largest = 0, se = 0; // se: 1 / sqrt(samples)
  bool symmetric = true;
};
NoiseMoments pair_noise_moments(const PairNoise& noise) {
  const std::size_t n = 1 << 21;
  NoiseMoments r;
  r.se = 1 / std::sqrt(2.0 * n);
  for (std::uint32_t k = 0; k < n; ++k) {
    double xi, zeta, xi2, zeta2;
    noise.pair(k, k + 1000003u, xi, zeta);
    noise.pair(k + 1000003u, k, xi2, zeta2);
    r.symmetric = r.symmetric && xi == xi2 && zeta == -zeta2;
    for (const double g : {xi, zeta}) {
      r.largest = std::max(r.largest, std::fabs(g));
      double p = 1;
      for (int e = 1; e <= 4; ++e) r.m[e] += (p *= g) / (2.0 * n);
    }
  }
  return r;
}
} // namespace

// The vectorisable Philox4x32-10 is Random123's, bit for bit; the libm-free Box-Muller gives
// standard Gaussians (moments of 2^21 pairs within 5 standard errors) and zeta_ij = -zeta_ji.
TEST(Noise, PhiloxIsRandom123AndGaussiansAreStandard) {
  const r123::Philox4x32::key_type key = {{0x12345678u, 0x9abcdefu}};
  for (std::uint32_t k = 0; k < 20000; ++k) {
    const r123::Philox4x32::ctr_type c = {{k, 7 * k + 3, k ^ 0x5555u, 0xffff0000u + k}};
    const auto r = r123::Philox4x32()(c, key);
    std::uint32_t r0, r1;
    philox4x32_10(c[0], c[1], c[2], c[3], key[0], key[1], r0, r1);
    ASSERT_EQ(r0, r[0]);
    ASSERT_EQ(r1, r[1]);
  }
  const NoiseMoments g = pair_noise_moments(PairNoise(42, 17, PairNoise::Pair));
  EXPECT_TRUE(g.symmetric);
  EXPECT_NEAR(g.m[1], 0, 5 * g.se);
  EXPECT_NEAR(g.m[2], 1, 5 * std::sqrt(2.0) * g.se);
  EXPECT_NEAR(g.m[3], 0, 5 * std::sqrt(15.0) * g.se);
  EXPECT_NEAR(g.m[4], 3, 5 * std::sqrt(96.0) * g.se);
}

// The libm-free, branch-free Box-Muller against libm's: radius sqrt(-2 ln u1), u1 = (a + 1/2)
// 2^-32, angle alpha = phi or pi/2 - phi (octant bit 0) + pi/2 (bit 1) + pi (bit 2), phi from the
// low 29 bits; the edge words of both conversions (0, 2^31 - 1, 2^31, 2^32 - 1, the mantissa's
// sqrt(2) split) and 2^20 words from Philox. ln u1 = e ln 2 + ln m - 32 ln 2 is good to ~1e-14
// absolute, so near u1 = 1 the radius carries that over itself.
TEST(Noise, BoxMullerIsLibmsToRoundOff) {
  const auto check = [](std::uint32_t a, std::uint32_t b) {
    double g1, g2;
    box_muller(a, b, g1, g2);
    const double radius = std::sqrt(-2 * std::log((a + 0.5) / 4294967296.0));
    const double phi = ((b & 0x1fffffffu) + 0.5) * (M_PI / 4 / 536870912.0);
    const std::uint32_t octant = b >> 29;
    const double alpha = ((octant & 1) ? M_PI / 2 - phi : phi) + ((octant & 2) ? M_PI / 2 : 0) +
                         ((octant & 4) ? M_PI : 0);
    const double allowed = 1e-13 * (1 + radius) + 2e-14 / radius;
    ASSERT_NEAR(g1, radius * std::cos(alpha), allowed) << a << " " << b;
    ASSERT_NEAR(g2, radius * std::sin(alpha), allowed) << a << " " << b;
  };
  for (const std::uint32_t a : {0u, 1u, 0x6a09e667u, 0x6a09e668u, 0x7fffffffu, 0x80000000u,
                                0xb504f333u, 0xb504f334u, 0xffffffffu})
    for (const std::uint32_t b :
         {0u, 0x1fffffffu, 0x20000000u, 0x5fffffffu, 0x9fffffffu, 0xe0000000u, 0xffffffffu})
      check(a, b);
  for (std::uint32_t k = 0; k < (1u << 20); ++k) {
    std::uint32_t a, b;
    philox4x32_10(k, 3, 5, 7, 11, 13, a, b);
    check(a, b);
  }
}

// The uniform pair noise (Particle/Noise = uniform): the same symmetry, mean 0, variance 1,
// inside (-sqrt 3, sqrt 3), and its fourth moment 9/5 (a uniform's, not a Gaussian's 3;
// E g^2n = 3^n / (2n + 1)).
TEST(Noise, UniformPairNoiseHasUnitVariance) {
  const NoiseMoments u = pair_noise_moments(PairNoise(42, 17, PairNoise::Pair, true));
  EXPECT_TRUE(u.symmetric);
  EXPECT_LT(u.largest, std::sqrt(3.0));
  EXPECT_NEAR(u.m[1], 0, 5 * u.se);
  EXPECT_NEAR(u.m[2], 1, 5 * std::sqrt(0.8) * u.se);        // Var(g^2) = 9/5 - 1
  EXPECT_NEAR(u.m[3], 0, 5 * std::sqrt(27.0 / 7) * u.se);   // E g^6 = 3^3 / 7
  EXPECT_NEAR(u.m[4], 1.8, 5 * std::sqrt(9 - 3.24) * u.se); // E g^8 = 3^4 / 9
}

// The pairs of the grid's list closer than rc = 1 now (the list also holds its skin's pairs).
template <class Sim> long listed_pairs_closer_than_rc(const Sim& sim) {
  long listed = 0;
  sim.grid().for_each_pair_block(
      [&](const std::uint32_t* I, const std::uint32_t* J, std::size_t n) {
        long mine = 0;
        for (std::size_t q = 0; q < n; ++q) {
          double dx[3], r2 = 0;
          sim.grid().separation(sim.state(), I[q], J[q], dx);
          for (int d = 0; d < 3; ++d) r2 += dx[d] * dx[d];
          mine += r2 < 1;
        }
#pragma omp atomic
        listed += mine;
      });
  return listed;
}

// The Verlet list (pairs within rc + skin) misses no pair closer than rc while it is kept, also
// past the global bound (a particle moved skin/2) where list_still_complete decides: after every
// step the listed pairs closer than rc are exactly those of an O(N^2) search, while the list is
// rebuilt only every few steps and is kept past the global bound in some of them. Hot particles
// (T = 4) and a 2D case with walls make the kept-past-bound steps frequent.
TEST(Neighbours, SkinListMissesNoPairBetweenRebuilds) {
  using Constant = Model<3, ConstantRepulsion, ConstantSigma, InverseSeed002Heat>;
  struct Case {
    Integrator integrator;
    bool walls;
  };
  for (const auto c : {Case{Integrator::EcVerlet, false}, Case{Integrator::Shardlow, false},
                       Case{Integrator::Shardlow, true}}) {
    auto p = seed002(c.integrator, 0.005);
    p.box = {{9, 9, 12}}; // 10 planes of cells: 5 even units, split unevenly by 3 and 4 threads
    p.conservative = ConservativeForce::Constant;
    p.neighbour_skin = 0.2;
    if (c.walls) p.walls[2] = WallPair{true, {{true, true}}, {{1, 1}}, true};
    const auto s002 = seed002_model(p);
    Simulation<Constant> sim(
        Constant{ConstantRepulsion{p.a0, 1, 1}, s002.friction, s002.heat, 1, p.cv, 1}, p);
    const auto& s = sim.state();
    const std::string name = std::string(to_string(c.integrator)) + (c.walls ? " with walls" : "");
    const long builds = sim.pair_list_builds();
    const int steps = 200;
    for (int k = 0; k < steps; ++k) {
      sim.step();
      long brute = 0;
      for (std::size_t i = 0; i < s.size(); ++i)
        for (std::size_t j = i + 1; j < s.size(); ++j) {
          double dx[3], r2 = 0;
          sim.grid().separation(s, i, j, dx);
          for (int d = 0; d < 3; ++d) r2 += dx[d] * dx[d];
          brute += r2 < 1;
        }
      const long listed = listed_pairs_closer_than_rc(sim);
      ASSERT_EQ(listed, brute) << name << " step " << k;
    }
    const long rebuilt = sim.pair_list_builds() - builds;
    EXPECT_LT(rebuilt, steps / 2) << name << ": the list is kept across steps";
    EXPECT_GT(rebuilt, 0) << name << ": and rebuilt when particles have moved";
    EXPECT_GT(sim.pair_list_kept_past_bound(), 0) << name << ": the check past the bound ran";
  }
}

// The check past the global bound finds a pair that is about to be missing: particle A, 0.15 per
// step towards B, which was listed 1.25 apart (beyond rc + skin = 1.2), the others far away.
// After one step A has moved past skin/2 but is 1.1 from B: the list is kept. After the second
// it is 0.95 from B, a pair the list lacks: the list must be rebuilt, and then holds it.
TEST(Neighbours, ListKeptPastTheBoundIsRebuiltForAnApproachingPair) {
  using Constant = Model<3, ConstantRepulsion, ConstantSigma, InverseSeed002Heat>;
  for (const auto integrator : {Integrator::EcVerlet, Integrator::Shardlow}) {
    auto p = seed002(integrator, 0.005);
    p.box = {{12, 12, 12}};
    p.density = 8.0 / 1728;
    p.conservative = ConservativeForce::Constant;
    p.neighbour_skin = 0.2;
    const auto s002 = seed002_model(p);
    Simulation<Constant> sim(
        Constant{ConstantRepulsion{p.a0, 1, 1}, s002.friction, s002.heat, 1, p.cv, 1}, p);
    auto& s = sim.state();
    ASSERT_EQ(s.size(), 8u);
    for (std::size_t k = 0; k < 8; ++k) { // A, B, and six alone at least 4 from everything
      const double far[6][3] = {{8, 2, 2}, {8, 8, 2}, {2, 8, 8}, {8, 2, 8}, {8, 8, 8}, {2, 2, 10}};
      const double at[3] = {k == 0   ? 2.0
                            : k == 1 ? 3.25
                                     : far[k - 2][0],
                            k < 2 ? 6 : far[k - 2][1], k < 2 ? 6 : far[k - 2][2]};
      for (int d = 0; d < 3; ++d) s.x[d][k] = at[d], s.v[d][k] = 0;
    }
    s.v[0][0] = 0.15 / p.dt; // particle A (storage index 0 before the sort)
    sim.resort();
    sim.prepare();
    const long builds = sim.pair_list_builds();
    sim.step();
    EXPECT_EQ(sim.pair_list_builds(), builds) << to_string(integrator);
    EXPECT_EQ(sim.pair_list_kept_past_bound(), 1) << to_string(integrator);
    EXPECT_EQ(listed_pairs_closer_than_rc(sim), 0) << to_string(integrator);
    sim.step();
    EXPECT_EQ(sim.pair_list_builds(), builds + 1) << to_string(integrator);
    EXPECT_EQ(listed_pairs_closer_than_rc(sim), 1)
        << to_string(integrator) << ": A and B, now 0.95 apart";
  }
}
