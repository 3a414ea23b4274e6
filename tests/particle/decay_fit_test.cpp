// The relaxation fit (particle/decay_fit.hpp) on synthetic decays whose truth is known: an exact
// exponential, and an exponential under the mode's own thermal noise (an Ornstein-Uhlenbeck
// process of constant size relaxing at the decay rate, as Onsager's regression says).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "particle/decay_fit.hpp"

namespace {

using twinflow::particle::decay_fit;

// The transport stage's 2D relaxation run at the default cavity's state: 1008 samples 0.45
// apart, rate 0.0134 (a heat mode), amplitude 0.95 after the first sample.
constexpr double kRate = 0.0134, kDt = 0.45;
constexpr int kSamples = 1008;

std::vector<double> times() {
  std::vector<double> t(kSamples);
  for (int i = 0; i < kSamples; ++i) t[i] = (i + 1) * kDt;
  return t;
}

TEST(DecayFit, ExactExponentialGivesItsRate) {
  const auto t = times();
  std::vector<double> a(kSamples);
  for (int i = 0; i < kSamples; ++i) a[i] = std::exp(-kRate * t[i]);
  const double k = 0.2;
  const auto j = decay_fit(k, t, a, "chi");
  ASSERT_TRUE(twinflow::io::find(j, {"chi"})) << j.dump();
  EXPECT_NEAR(twinflow::io::find(j, {"decay_rate"})->get<double>(), kRate, 1e-9 * kRate);
  EXPECT_NEAR(twinflow::io::find(j, {"chi"})->get<double>(), kRate / (k * k),
              1e-9 * kRate / (k * k));
}

TEST(DecayFit, TooShortARunSaysSo) {
  const auto t = times();
  std::vector<double> a(kSamples);
  for (int i = 0; i < kSamples; ++i) a[i] = std::exp(-0.1 * kRate * t[i]); // never below 30%
  const auto j = decay_fit(0.2, t, a, "chi");
  EXPECT_FALSE(j.contains("chi"));
  EXPECT_TRUE(j.contains("note"));
}

// 400 noisy decays at noise 5% of the amplitude (the measured level in the 2D runs): the mean
// rate is unbiased within 4 standard errors of the mean, and the fits' stated error matches the
// rates' scatter (the scatter's own sampling error is 1/sqrt(2 * 399) = 3.5%; the widening for
// the noise's correlation is the AR(1) approximation, good to ~10% in a window of a few
// correlation times, hence the band 0.8-1.25).
TEST(DecayFit, StatedErrorMatchesTheScatterUnderCorrelatedNoise) {
  const auto t = times();
  std::mt19937_64 rng(2026);
  std::normal_distribution<double> normal;
  const double noise = 0.05, c = std::exp(-kRate * kDt);
  const int draws = 400;
  std::vector<double> rates, errors;
  for (int d = 0; d < draws; ++d) {
    std::vector<double> a(kSamples);
    double x = noise * normal(rng);
    for (int i = 0; i < kSamples; ++i) {
      x = c * x + std::sqrt(1 - c * c) * noise * normal(rng);
      a[i] = 0.95 * std::exp(-kRate * t[i]) + x;
    }
    const auto j = decay_fit(0.2, t, a, "chi");
    ASSERT_TRUE(twinflow::io::find(j, {"decay_rate"})) << j.dump();
    rates.push_back(twinflow::io::find(j, {"decay_rate"})->get<double>());
    errors.push_back(twinflow::io::find(j, {"decay_rate_stderr"})->get<double>());
  }
  double mean = 0;
  for (const double r : rates) mean += r / draws;
  double var = 0;
  for (const double r : rates) var += (r - mean) * (r - mean) / (draws - 1);
  const double sd = std::sqrt(var);
  std::nth_element(errors.begin(), errors.begin() + draws / 2, errors.end());
  const double median_error = errors[draws / 2];
  std::printf("rate %.5f (true %.5f), scatter %.5f, median stated error %.5f\n", mean, kRate, sd,
              median_error);
  EXPECT_NEAR(mean, kRate, 4 * sd / std::sqrt(draws));
  EXPECT_GT(median_error / sd, 0.8);
  EXPECT_LT(median_error / sd, 1.25);
}

} // namespace
