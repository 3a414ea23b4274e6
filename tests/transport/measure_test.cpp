// Measured coefficients: repeats and their error, and the relaxation runs behind kappa and eta.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>

#include "../particle/helpers.hpp"
#include "particle/seeds.hpp"
#include "transport/estimates.hpp"
#include "transport/measure.hpp"
#include "transport/measurement.hpp"

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
  // A failed fit is left out and counted, not averaged into NaN.
  const Repeated failed = summarise_repeats({{10, 0.1}, {std::nan(""), std::nan("")}, {14, 0.1}});
  EXPECT_DOUBLE_EQ(failed.value.mean, 12);
  EXPECT_EQ(failed.failed, 1);
}

// D's rule: the spread's alone, with its degrees of freedom, even when the fits say more; one run
// falls back to its fit's error (dof 0).
TEST(RepeatedMeasurement, SpreadRuleStatesTheSpreadAndItsDegreesOfFreedom) {
  const Repeated spread = summarise_repeats({{5, 3}, {6, 3}, {7, 3}}, RepeatError::Spread);
  EXPECT_NEAR(spread.value.stderr_, 1 / std::sqrt(3.0), 1e-12); // sd 1 over sqrt(3)
  EXPECT_EQ(spread.dof, 2);
  EXPECT_NEAR(spread.fit_stderr, std::sqrt(3.0), 1e-12); // reported beside it
  const Repeated larger = summarise_repeats({{5, 3}, {6, 3}, {7, 3}});
  EXPECT_NEAR(larger.value.stderr_, std::sqrt(3.0), 1e-12);
  EXPECT_EQ(larger.dof, 0);
  const Repeated one = summarise_repeats({{7, 0.5}}, RepeatError::Spread);
  EXPECT_DOUBLE_EQ(one.value.stderr_, 0.5);
  EXPECT_EQ(one.dof, 0);
}

// Repeat seeds: repeat 0 is the base seed; no repeat of one base seed equals a repeat (or the
// base) of another, also for bases that differ by the old additive step (7727).
TEST(RepeatedMeasurement, RepeatSeedsOfDifferentBasesNeverCoincide) {
  using particle::derived_seed;
  using particle::SeedPurpose;
  std::set<std::uint64_t> seen;
  std::size_t made = 0;
  for (std::uint64_t base : {1ull, 2ull, 7728ull, 15455ull, 1000003ull, 6000018ull})
    for (std::uint64_t r = 0; r < 100; ++r, ++made) {
      const std::uint64_t s = derived_seed(base, SeedPurpose::DiffusionRepeat, r);
      if (r == 0) {
        EXPECT_EQ(s, base);
      }
      seen.insert(s);
    }
  EXPECT_EQ(seen.size(), made);
}

// A small 2D ideal DPDE box: the heat and the transverse momentum modes both decay and give
// positive coefficients (a repeat whose fit failed left out); each repeat has its own seed (they
// differ), and the mean's error is at least the spread's. Against theory only the order of
// magnitude, within a factor 3 (the 2D estimates are off by up to ~2 at these states:
// docs/validation.md, "Transport coefficients").
TEST(RelaxationMeasurement, HeatAndShearModesGiveCoefficientsWithRepeatErrors) {
  auto p = particle::testing::ideal(2, particle::Integrator::Shardlow, 10);
  p.box = {{8, 8, 1}};
  p.dt = 0.01;
  const Estimates e = estimate(p, p.temperature, PairDistribution::ideal());
  const RelaxationCoefficients m = measure_relaxation(p, e, e.heat_capacity_p, 3);
  ASSERT_EQ(m.conductivity.repeats.size(), 3u);
  ASSERT_EQ(m.viscosity.repeats.size(), 3u);
  EXPECT_NE(m.conductivity.repeats[0].mean, m.conductivity.repeats[1].mean);
  // In a box this small the heat mode can sink into its noise before the fit has its points:
  // such a repeat is dropped and counted. Measured over seeds 1000-20000 (60 runs): 3 heat-mode
  // fits failed with one version of the pair list's rebuild rule, 0 with the next; no shear-mode
  // fit. Two of three failing would be a ~1% event.
  for (const Repeated* r : {&m.conductivity, &m.viscosity}) {
    EXPECT_TRUE(std::isfinite(r->value.mean));
    EXPECT_LE(r->failed, 1);
    EXPECT_GT(r->value.stderr_, 0);
  }
  // The runs' own temperature: near the state point, a little above it (the shear mode's
  // kinetic energy ends as heat: U^2 k T / 4 per particle over c_v + 1 + d/2).
  EXPECT_GT(m.temperature.value.mean, p.temperature);
  EXPECT_LT(m.temperature.value.mean, p.temperature * (1 + 0.25 / (p.cv + 2) + 0.01));
  std::printf("kappa %.3f +- %.3f (estimate %.3f), eta %.3f +- %.3f (estimate %.3f); %ld "
              "particles, %ld steps\n",
              m.conductivity.value.mean, m.conductivity.value.stderr_, e.conductivity,
              m.viscosity.value.mean, m.viscosity.value.stderr_, e.viscosity, m.particles, m.steps);
  EXPECT_GT(m.conductivity.value.mean, e.conductivity / 3);
  EXPECT_LT(m.conductivity.value.mean, e.conductivity * 3);
  EXPECT_GT(m.viscosity.value.mean, e.viscosity / 3);
  EXPECT_LT(m.viscosity.value.mean, e.viscosity * 3);
}

// Points on an exact power law give back its value and exponent; with noise, the stated
// exponent error matches the scatter of the fitted exponents over many noisy draws.
TEST(RepeatedMeasurement, PowerLawThroughThreeTemperatures) {
  const double t_ref = 0.8, value = 16, n = -0.7, e = 0.05;
  const std::vector<double> t{0.56, 0.8, 1.04};
  std::vector<Estimate> exact;
  for (const double ti : t) exact.push_back({value * std::pow(ti / t_ref, n), 0});
  for (auto& p : exact) p.stderr_ = e * p.mean;
  const PowerLawFit f = fit_power_law(t, exact, t_ref);
  EXPECT_NEAR(f.exponent, n, 1e-12);
  EXPECT_NEAR(f.value, value, 1e-12 * value);
  EXPECT_NEAR(f.chi2_per_dof, 0, 1e-20);

  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss;
  const int draws = 4000;
  double sum = 0, sum2 = 0;
  for (int k = 0; k < draws; ++k) {
    std::vector<Estimate> noisy = exact;
    for (auto& p : noisy) p.mean *= std::exp(e * gauss(rng)); // relative error e
    const double x = fit_power_law(t, noisy, t_ref).exponent;
    sum += x, sum2 += x * x;
  }
  const double sd = std::sqrt(sum2 / draws - std::pow(sum / draws, 2));
  // The sample sd of 4000 draws is itself uncertain by 1/sqrt(2 * 4000) = 1.1%: 5% is 4.5 of that.
  EXPECT_NEAR(sd / f.exponent_stderr, 1, 0.05);
  EXPECT_NEAR(sum / draws, n, 4 * sd / std::sqrt(draws));
}

// The excess pressure p - n T = n^2 (b0 + b1 T + b2 (n - n_ref)) through the five state points
// of the transport stage (T +- 5%, n +- 5%): exact points give b0, b1, b2 back; with noise, the
// stated errors match the scatter of the fits over many draws.
TEST(ExcessPressureFit, FivePointsGiveTheCoefficientsAndHonestErrors) {
  const double b0 = 2.3, b1 = -0.05, b2 = 0.13, n = 3, T = 1.25, h = 0.05, se = 0.008;
  std::vector<PressurePoint> exact;
  for (const auto& [ni, ti] : std::vector<std::pair<double, double>>{
           {n, T}, {n, T * (1 + h)}, {n, T * (1 - h)}, {n * (1 + h), T}, {n * (1 - h), T}})
    exact.push_back({ni, ti, {ni * ti + ni * ni * (b0 + b1 * ti + b2 * (ni - n)), se}});
  const ExcessPressureFit f = fit_excess_pressure(exact, n);
  EXPECT_NEAR(f.b0, b0, 1e-10);
  EXPECT_NEAR(f.b1, b1, 1e-10);
  EXPECT_NEAR(f.b2, b2, 1e-10);
  EXPECT_EQ(f.dof, 2);
  EXPECT_NEAR(f.chi2_per_dof, 0, 1e-16);

  std::mt19937_64 rng(11);
  std::normal_distribution<double> gauss;
  const int draws = 4000;
  std::array<double, 3> sum{}, sum2{}, stated{};
  for (int k = 0; k < draws; ++k) {
    std::vector<PressurePoint> noisy = exact;
    for (auto& p : noisy) p.pressure.mean += se * gauss(rng);
    const ExcessPressureFit g = fit_excess_pressure(noisy, n);
    const std::array<double, 3> b{g.b0, g.b1, g.b2}, e{g.b0_stderr, g.b1_stderr, g.b2_stderr};
    // The errors before the chi^2 scaling (which only grows them): the same for every draw
    const double scale = std::sqrt(std::max(1.0, g.chi2_per_dof));
    for (int i = 0; i < 3; ++i) sum[i] += b[i], sum2[i] += b[i] * b[i], stated[i] = e[i] / scale;
  }
  const std::array<double, 3> truth{b0, b1, b2};
  for (int i = 0; i < 3; ++i) {
    const double mean = sum[i] / draws, sd = std::sqrt(sum2[i] / draws - mean * mean);
    std::printf("  b%d %.5f +- %.5f (stated %.5f)\n", i, mean, sd, stated[i]);
    // 4000 draws: the sample sd is uncertain by 1.1%; 5% is 4.5 of that.
    EXPECT_NEAR(sd / stated[i], 1, 0.05);
    EXPECT_NEAR(mean, truth[i], 4 * sd / std::sqrt(draws));
  }
}

// The transport stage's five bulk runs of a soft-repulsion fluid (2D, n = 4, a0 = 5, N = 1024):
// the excess-pressure fit describes them (chi^2 per dof within its 99.9% range for 2 dof), and
// its B at the state point lies near the mean-field value with g(r) = 1,
// (pi / 2) a0 int_0^1 r^2 (1 - r) dr = (pi / 24) a0 (the 2D virial; the measured g(r) < 1 inside
// the cutoff makes it ~8% smaller: 0.604 against 0.654 in a 20 x 20 box). The ideal fluid: B = 0
// within the fit's errors.
TEST(ExcessPressureFit, SoftRepulsionFluidIsDescribed) {
  for (const double a0 : {5.0, 0.0}) {
    auto p = particle::testing::ideal(2, particle::Integrator::Shardlow, 10);
    p.density = 4;
    p.dt = 0.01;
    if (a0 > 0) p.conservative = particle::ConservativeForce::Constant, p.a0 = a0;
    const Measured m = measure(p, 2000, 2);
    const ExcessPressureFit& f = m.excess_pressure;
    const double B = f.b0 + f.b1 * m.temperature.mean;
    const double B_stderr =
        std::sqrt(f.covariance(0, 0) + 2 * m.temperature.mean * f.covariance(0, 1) +
                  std::pow(m.temperature.mean, 2) * f.covariance(1, 1));
    std::printf("  a0 %g: B = %.4f +- %.4f at T %.3f (mean field %.4f), b1 %.4f +- %.4f, b2 "
                "%.4f +- %.4f, chi2/dof %.2f\n",
                a0, B, B_stderr, m.temperature.mean, M_PI / 24 * a0, f.b1, f.b1_stderr, f.b2,
                f.b2_stderr, f.chi2_per_dof);
    EXPECT_EQ(f.dof, 2);
    EXPECT_LT(f.chi2_per_dof, 6.9);
    if (a0 > 0) {
      EXPECT_GT(B, 0.8 * M_PI / 24 * a0);
      EXPECT_LT(B, 1.0 * M_PI / 24 * a0);
    } else {
      EXPECT_LT(std::abs(B), 4 * B_stderr);
    }
  }
}

// The slabs' profile is read along their own direction: the same fluid with its slabs along x and
// along y gives the same windows (the column case's slabs, along y, were once read along x's
// single bin: one window at the box's mean, K off by 5x), and the pair part measured in them, which
// the law takes.
TEST(SlabKappa, WindowsFollowTheSlabsDirection) {
  std::array<std::vector<StatePoint>, 2> points;
  std::array<particle::Estimate, 2> pair;
  for (int dir : {0, 1}) {
    auto p = particle::testing::ideal(2, particle::Integrator::Shardlow, 10);
    const double half = 10;
    p.box = {{4, 4, 1}};
    p.box[dir] = 2 * half;
    p.bins = {{1, 1, 1}};
    p.bins[dir] = 40;
    p.heat_slabs = {{dir, half, half + 1, 2.0}, {dir, 0, 1, -2.0}};
    p.equilibration_steps = 2000, p.steps = 4000, p.sample_interval = 10;
    const SlabKappa r = kappa_from_slabs(p, p.density, p.temperature, 0, -1, 1);
    points[dir] = r.points;
    pair[dir] = r.pair;
    EXPECT_GT(r.pair.mean, 0) << "the pair conduction's part, measured, direction " << dir;
    EXPECT_GT(r.pair.stderr_, 0);
    EXPECT_EQ(r.law.P, r.pair.mean) << "the law takes the measured pair part";
    ASSERT_EQ(r.points.size(), 4u) << "direction " << dir; // 2 windows of 3 rc per half
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (const StatePoint& s : r.points) lo = std::min(lo, s.T), hi = std::max(hi, s.T);
    EXPECT_GT(hi - lo, 0.05) << "the windows see the profile's span, direction " << dir;
  }
  ASSERT_EQ(points[0].size(), points[1].size());
  // The same fluid along x and along y: the measured pair parts agree within their errors.
  EXPECT_LT(std::fabs(pair[0].mean - pair[1].mean),
            3 * std::hypot(pair[0].stderr_, pair[1].stderr_));
}
