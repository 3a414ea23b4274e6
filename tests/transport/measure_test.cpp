// Measured coefficients: repeats and their error, and the relaxation runs behind kappa and eta.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../particle/helpers.hpp"
#include "transport/estimates.hpp"
#include "transport/measure.hpp"

using namespace twinflow;
using namespace twinflow::transport;
using particle::Estimate;

// The stated error is the standard error of the mean from the repeats' spread, unless the fits'
// own errors are larger (a small spread of few repeats can be luck).
TEST(RepeatedMeasurement, ErrorIsTheLargerOfSpreadAndFits) {
  // Spread dominates: values 10, 12, 14 (sd 2), fit errors 0.1.
  const Repeated wide = summarise_repeats({{10, 0.1}, {12, 0.1}, {14, 0.1}});
  EXPECT_DOUBLE_EQ(wide.value.mean, 12);
  EXPECT_NEAR(wide.spread_stderr, 2 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(wide.value.stderr_, wide.spread_stderr, 1e-12);
  // Fits dominate: identical values, fit errors 3 each -> 3 / sqrt(3).
  const Repeated narrow = summarise_repeats({{5, 3}, {5, 3}, {5, 3}});
  EXPECT_DOUBLE_EQ(narrow.spread_stderr, 0);
  EXPECT_NEAR(narrow.value.stderr_, std::sqrt(3.0), 1e-12);
  // One run: its fit's error.
  const Repeated one = summarise_repeats({{7, 0.5}});
  EXPECT_DOUBLE_EQ(one.value.stderr_, 0.5);
}

// A small 2D ideal DPDE box: the heat and the transverse momentum modes both decay and give
// positive coefficients; each repeat has its own seed (they differ), and the mean's error is at
// least the spread's. Against theory only the order of magnitude, within a factor 3 (the 2D
// estimates are off by up to ~2 at these states: README, transport table).
TEST(RelaxationMeasurement, HeatAndShearModesGiveCoefficientsWithRepeatErrors) {
  auto p = particle::testing::ideal(2, particle::Integrator::Shardlow, 10);
  p.box = {{8, 8, 1}};
  p.dt = 0.01;
  const Estimates e = estimate(p, p.temperature, PairDistribution::ideal());
  const RelaxationCoefficients m = measure_relaxation(p, e, e.heat_capacity_p, 3);
  ASSERT_EQ(m.conductivity.repeats.size(), 3u);
  ASSERT_EQ(m.viscosity.repeats.size(), 3u);
  EXPECT_NE(m.conductivity.repeats[0].mean, m.conductivity.repeats[1].mean);
  for (const Repeated* r : {&m.conductivity, &m.viscosity}) {
    EXPECT_TRUE(std::isfinite(r->value.mean));
    EXPECT_GE(r->value.stderr_, r->spread_stderr);
    EXPECT_GT(r->value.stderr_, 0);
  }
  std::printf("kappa %.3f +- %.3f (estimate %.3f), eta %.3f +- %.3f (estimate %.3f); %ld "
              "particles, %ld steps\n",
              m.conductivity.value.mean, m.conductivity.value.stderr_, e.conductivity,
              m.viscosity.value.mean, m.viscosity.value.stderr_, e.viscosity, m.particles, m.steps);
  EXPECT_GT(m.conductivity.value.mean, e.conductivity / 3);
  EXPECT_LT(m.conductivity.value.mean, e.conductivity * 3);
  EXPECT_GT(m.viscosity.value.mean, e.viscosity / 3);
  EXPECT_LT(m.viscosity.value.mean, e.viscosity * 3);
}

// Points on an exact power law give back its value and exponent; the exponent's error follows
// from the points' errors as for a straight line in logs (three points at x = -h, 0, h with
// equal relative errors e: stderr = e / (h sqrt(2))).
TEST(RepeatedMeasurement, PowerLawThroughThreeTemperatures) {
  const double t_ref = 0.8, value = 16, n = -0.7, e = 0.05;
  std::vector<double> t{0.56, 0.8, 1.04};
  std::vector<Estimate> v;
  for (const double ti : t) v.push_back({value * std::pow(ti / t_ref, n), e * value});
  for (auto& p : v) p.stderr_ = e * p.mean;
  const PowerLawFit f = fit_power_law(t, v, t_ref);
  EXPECT_NEAR(f.exponent, n, 1e-12);
  EXPECT_NEAR(f.value, value, 1e-12 * value);
  EXPECT_NEAR(f.chi2_per_dof, 0, 1e-20);
  // Unequal spacing in logs: check against the weighted-line formula directly.
  double sx = 0, sxx = 0;
  for (const double ti : t) sx += std::log(ti / t_ref), sxx += std::pow(std::log(ti / t_ref), 2);
  const double w = 1 / (e * e), det = w * w * (3 * sxx - sx * sx);
  EXPECT_NEAR(f.exponent_stderr, std::sqrt(3 * w / det), 1e-12);
}
