// Block statistics (statistics/blocking.hpp) against answers known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "statistics/blocking.hpp"
#include "statistics/line_fit.hpp"

using namespace twinflow::statistics;

namespace {

// An AR(1) series x_t = phi x_(t-1) + e_t, e_t ~ N(0, 1), started in its stationary state.
std::vector<double> ar1(double phi, std::size_t n, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> x(n);
  x[0] = normal(rng) / std::sqrt(1 - phi * phi);
  for (std::size_t t = 1; t < n; ++t) x[t] = phi * x[t - 1] + normal(rng);
  return x;
}

// Var(mean of n samples) of that series, exactly: (s^2 / n) [(1 + phi) / (1 - phi)
// - 2 phi (1 - phi^n) / (n (1 - phi)^2)] with s^2 = 1 / (1 - phi^2).
double ar1_variance_of_mean(double phi, double n) {
  const double s2 = 1 / (1 - phi * phi);
  return s2 / n *
         ((1 + phi) / (1 - phi) - 2 * phi * (1 - std::pow(phi, n)) / (n * (1 - phi) * (1 - phi)));
}

} // namespace

// Correlated data (memory ~ 10 samples): blocks of 1000 samples give the true standard error of
// the mean, which is 3x the one that takes the samples as independent.
TEST(Statistics, BlockingErrorOfCorrelatedSeriesIsTheTrueOne) {
  const double phi = 0.8;
  const std::size_t n = 20000, replicas = 400;
  std::mt19937_64 rng(2024);
  double blocked2 = 0, naive2 = 0, scatter2 = 0;
  for (std::size_t r = 0; r < replicas; ++r) {
    const std::vector<double> x = ar1(phi, n, rng);
    const std::vector<double> levels = blocking_errors(x, 20);
    ASSERT_EQ(levels.size(), 3u); // 20, 10 and 5 blocks
    blocked2 += levels[0] * levels[0] / replicas;
    naive2 += std::pow(block_average(x, static_cast<int>(n)).stderr_, 2) / replicas;
    scatter2 += std::pow(block_average(x, 20).mean, 2) / replicas; // the true mean is 0
  }
  const double truth = ar1_variance_of_mean(phi, n);
  // Mean of 400 estimates with 19 degrees of freedom: 1.6% statistical spread; the blocks' own
  // correlation biases them low by ~1%.
  EXPECT_NEAR(blocked2 / truth, 1.0, 0.06);
  EXPECT_NEAR(scatter2 / truth, 1.0, 0.25);                 // 400 squared normals: 7% spread
  EXPECT_NEAR(naive2 / truth, (1 - phi) / (1 + phi), 0.01); // blind to the correlation
}

// Block means 1, 1, 0, 0, 1, 1, 0, 0 (a slow square wave): the error grows when pairs of blocks
// merge, and vanishes when fours do (each four holds one period).
TEST(Statistics, BlockingLevelsOfASquareWave) {
  std::vector<double> series;
  for (int b = 0; b < 8; ++b)
    for (int k = 0; k < 5; ++k) series.push_back(b % 4 < 2 ? 1.0 : 0.0);
  series.push_back(7.0); // a remainder shorter than a block: in the mean only
  const Estimate e = block_average(series, 8);
  EXPECT_DOUBLE_EQ(e.mean, 27.0 / 41);
  const std::vector<double> levels = blocking_errors(series, 8);
  ASSERT_EQ(levels.size(), 3u);
  EXPECT_DOUBLE_EQ(levels[0], std::sqrt(8 * 0.25 / (7 * 8)));
  EXPECT_DOUBLE_EQ(levels[1], std::sqrt(4 * 0.25 / (3 * 4)));
  EXPECT_DOUBLE_EQ(levels[2], 0.0);
  EXPECT_EQ(blocking_errors(series, 3).size(), 1u); // 3 blocks; 1 is no error
}

// Per-block estimates, merged in adjacent groups; a partial last group is left out.
TEST(Statistics, MergedBlockEstimates) {
  const std::vector<double> blocks = {1, 1, 0, 0, 1, 1, 0, 0, 5};
  const Estimate e = block_estimate(blocks);
  EXPECT_DOUBLE_EQ(e.mean, 1.0);
  const std::vector<double> levels = merged_blocking_errors(blocks);
  ASSERT_EQ(levels.size(), 3u);
  EXPECT_DOUBLE_EQ(levels[0], e.stderr_);
  EXPECT_DOUBLE_EQ(levels[1], std::sqrt(4 * 0.25 / (3 * 4))); // 1, 0, 1, 0
  EXPECT_DOUBLE_EQ(levels[2], 0.0);                           // 0.5, 0.5
  EXPECT_EQ(block_estimate({2.0}).stderr_, 0.0);
  EXPECT_TRUE(merged_blocking_errors({2.0}).empty());
}

// Many bins whose series share a memory comparable with a block (AR(1), phi = 0.97: ~65 samples;
// 20 blocks of 50): each bin's block error is short of the true one, and the pooled factor
// (statistics::PooledBlocking) brings it back; for independent samples the factor stays ~1.
TEST(Statistics, PooledBlockingFactorRestoresTheErrorOfShortBlocks) {
  const std::size_t n = 1000, bins = 400;
  const int blocks = 20;
  for (const double phi : {0.97, 0.0}) {
    std::mt19937_64 rng(77);
    PooledBlocking pooled;
    double first2 = 0, scatter2 = 0;
    for (std::size_t b = 0; b < bins; ++b) {
      const std::vector<double> per_block = block_means(ar1(phi, n, rng), blocks);
      pooled.add(per_block);
      const Estimate e = block_estimate(per_block);
      first2 += e.stderr_ * e.stderr_ / bins;
      scatter2 += e.mean * e.mean / bins; // the true mean is 0
    }
    const double truth = ar1_variance_of_mean(phi, n);
    EXPECT_NEAR(scatter2 / truth, 1.0, 0.2); // 400 squared normals: 7% spread
    if (phi > 0) {
      EXPECT_LT(first2 / truth, 0.7); // the blocks alone: short
      // 5 blocks of 200 samples still miss ~1/6 of a 65-sample memory's variance (0.79-0.89
      // over ten generator seeds), against half for the blocks alone
      EXPECT_NEAR(pooled.factor() * pooled.factor() * first2 / truth, 0.84, 0.1);
    } else {
      EXPECT_NEAR(first2 / truth, 1.0, 0.1);
      EXPECT_GE(pooled.factor(), 1.0);
      EXPECT_LT(pooled.factor(), 1.1);
    }
  }
}

TEST(Statistics, LineThroughExactPoints) {
  LineFit fit;
  for (double x : {0.0, 1.0, 2.0, 4.0}) fit.add(x, 3 - 0.5 * x, 0.1);
  EXPECT_NEAR(fit.slope(), -0.5, 1e-14);
  EXPECT_NEAR(fit.intercept(), 3.0, 1e-14);
  // Four points of error 0.1: var(slope) = 0.01 / sum (x - <x>)^2 = 0.01 / 8.75
  EXPECT_NEAR(fit.slope_stderr(), 0.1 / std::sqrt(8.75), 1e-14);
}

TEST(Statistics, ParabolaThroughExactPoints) {
  QuadraticFit fit(2.0);
  for (double x : {0.0, 1.0, 2.5, 4.0, 5.0}) fit.add(x, 1 + 0.3 * x - 0.05 * x * x, 0.1);
  EXPECT_NEAR(fit.value(0), 1, 1e-12);
  EXPECT_NEAR(fit.slope(3), 0.3 - 0.1 * 3, 1e-12);
  EXPECT_NEAR(fit.curvature(), -0.1, 1e-12);
  // Three points fix the parabola: it passes through each, with that point's own error there,
  // and its slope between two is their chord's (x = 0, 2: the midpoint x = 1).
  QuadraticFit three;
  three.add(0, 1, 0.1), three.add(2, 2, 0.2), three.add(4, 0, 0.3);
  for (const auto& [x, se] : {std::pair{0.0, 0.1}, {2.0, 0.2}, {4.0, 0.3}})
    EXPECT_NEAR(three.value_stderr(x), se, 1e-12);
  EXPECT_NEAR(three.slope(1), 0.5, 1e-12);
  EXPECT_NEAR(three.slope_stderr(1), std::hypot(0.1, 0.2) / 2, 1e-12);
}
