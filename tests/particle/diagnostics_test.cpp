// The diagnostics a scene creates (particle/diagnostics/diagnostics.hpp): only the ones it needs.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.hpp"
#include "particle/diagnostics/diagnostics.hpp"
#include "particle/diagnostics/plugins.hpp"
#include "particle/fields.hpp"

using namespace twinflow::particle;

namespace {

template <int D> std::vector<std::string> names(const ParticleParameters& p, bool has_energy) {
  RunFacts m;
  m.particles = 100;
  m.has_energy = has_energy;
  std::vector<std::string> out;
  for (const auto& d : make_diagnostics<D>(p, m)) out.push_back(d->name());
  return out;
}

const std::vector<std::string> kAlways = {"thermo", "histograms", "pair_distribution",
                                          "correlations", "fields"};

} // namespace

// A periodic box without walls, slabs, body force or perturbation: none of their plug-ins.
TEST(Diagnostics, PlainSceneHasNoSceneSpecificPlugins) {
  const ParticleParameters p = twinflow::particle::testing::ideal(3, Integrator::Shardlow, 10);
  EXPECT_EQ(names<3>(p, true), kAlways);
}

TEST(Diagnostics, EachSceneAddsItsOwn) {
  ParticleParameters p = twinflow::particle::testing::ideal(2, Integrator::Shardlow, 10);
  p.walls[0] = WallPair{true, {{true, true}}, {{1.5, 0.5}}, true};
  p.bins = {{8, 1, 1}};
  EXPECT_EQ(names<2>(p, true),
            (std::vector<std::string>{"thermo", "wall_fluxes", "wall_layers", "histograms",
                                      "pair_distribution", "correlations", "fields",
                                      "wall_profile_fit"}));
  p.bins = {{8, 8, 1}}; // no 1D profile across the walls: no Kapitza fit
  EXPECT_EQ(names<2>(p, true).back(), "fields");

  p = twinflow::particle::testing::ideal(3, Integrator::Shardlow, 10);
  p.heat_slabs = {HeatSlab{0, 3, 3.5, 20}, HeatSlab{0, 0, 0.5, -20}};
  p.poiseuille_force = 0.1;
  p.temperature_perturbation = 0.1;
  EXPECT_EQ(names<3>(p, true),
            (std::vector<std::string>{"thermo", "histograms", "pair_distribution", "correlations",
                                      "relaxation_modes", "fields", "poiseuille_fit",
                                      "slab_profile", "slab_kappa_fit"}));
  // Isothermal DPD: no heat mode and no slab kappa (no internal energies).
  p.poiseuille_force = 0;
  EXPECT_EQ(names<3>(p, false),
            (std::vector<std::string>{"thermo", "histograms", "pair_distribution", "correlations",
                                      "fields", "slab_profile"}));
}

// wall_profile_fit on a made profile: a parabola in the bulk with known wall values, and a wall
// layer (within one cutoff) held at the walls' temperatures, which the fit must leave out. The
// jumps are T_wall - the bulk's value at the wall, the slope the profile's at the centre.
TEST(Diagnostics, WallProfileFitsTheBulkAndCarriesItAcrossTheWallLayer) {
  ParticleParameters p = twinflow::particle::testing::ideal(3, Integrator::Shardlow, 10);
  p.box = {{16, 10, 10}};
  p.walls[0] = WallPair{true, {{true, true}}, {{1.2, 0.8}}, false};
  p.bins = {{32, 1, 1}};
  ASSERT_EQ(wall_profile_direction(p), 0);
  ASSERT_DOUBLE_EQ(p.largest_cutoff(), 1.0);
  const double at_lower = 1.19, at_upper = 0.805, curvature = -4e-4, length = 16;
  // T(x) = at_lower + b x + c x^2 / 2 with T(L) = at_upper
  const double b = (at_upper - at_lower) / length - 0.5 * curvature * length;
  const auto bulk = [&](double x) { return at_lower + b * x + 0.5 * curvature * x * x; };
  BinnedFields f;
  f.bins = p.bins, f.box = p.box, f.dim = 3;
  for (int bin = 0; bin < 32; ++bin) {
    const double x = f.centre(bin, 0);
    const double t = x < 1 ? 1.2 : x > length - 1 ? 0.8 : bulk(x);
    f.temperature_internal.mean.push_back(t);
    f.temperature_internal.stderr_.push_back(0.003);
  }
  for (int k = 0; k < 4; ++k) { // blocks scattered about the mean, one down, one up, ...
    auto block = f.temperature_internal.mean;
    for (double& t : block) t += (k % 2 ? 0.01 : -0.01);
    f.temperature_internal_blocks.push_back(block);
  }
  const auto j = wall_profile_fit(p, 0, f);
  EXPECT_NEAR(j["jump_lower"].get<double>(), 1.2 - at_lower, 1e-12);
  EXPECT_NEAR(j["jump_upper"].get<double>(), 0.8 - at_upper, 1e-12);
  EXPECT_NEAR(j["slope"].get<double>(), b + curvature * 0.5 * length, 1e-12);
  EXPECT_NEAR(j["curvature"].get<double>(), curvature, 1e-12);
  EXPECT_DOUBLE_EQ(j["jump_fit_from"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["jump_fit_to"].get<double>(), 15.0);
  // Blocks offset by -+0.01 alternately: their wall values scatter the same, a standard error
  // (4 blocks) larger than the fit's from 28 bins of 0.003, and the stated one.
  EXPECT_GT(0.01 * std::sqrt(4.0 / 3) / 2, j["jump_lower_stderr_fit"].get<double>());
  EXPECT_NEAR(j["jump_lower_stderr"].get<double>(), 0.01 * std::sqrt(4.0 / 3) / 2, 1e-12);
}

// A reverse Poiseuille flow between walls along y, made: each half a parabola of curvature
// -+n F / eta whose root lies b_lower beyond the lower wall and b_upper beyond the upper, a layer
// within one cutoff of each wall that the fit must leave out. The fit gives back eta and both
// slips; the slips' errors are the sum over bins of (d slip / d v_bin)^2 se^2, the derivatives
// by re-fitting with one bin moved.
TEST(Diagnostics, PoiseuilleBetweenWallsGivesEachWallsSlip) {
  ParticleParameters p = twinflow::particle::testing::ideal(2, Integrator::Shardlow, 10);
  p.box = {{10, 20, 1}};
  p.bins = {{1, 40, 1}};
  p.walls[1] = WallPair{true, {{false, false}}, {{1, 1}}, true};
  p.density = 4, p.poiseuille_force = 0.01;
  ASSERT_DOUBLE_EQ(p.largest_cutoff(), 1.0);
  const double eta = 1.3, b_lower = 0.4, b_upper = 0.15, a = p.density * p.poiseuille_force / eta;
  const auto made = [&](double y) {  // each half its own parabola (the fit takes them apart)
    if (y < 1 || y > 19) return 0.0; // the walls' layers
    const double top = 10 + (10 - b_lower) * 0.3;
    if (y < 10) return -0.5 * a * (y + b_lower) * (y - top);
    return 0.5 * a * (y - 20 - b_upper) * (y - 20 + (10 - b_upper) * 0.6);
  };
  BinnedFields f;
  f.bins = p.bins, f.box = p.box, f.dim = 2;
  const double se = 0.002;
  for (int bin = 0; bin < 40; ++bin) {
    f.velocity.mean.insert(f.velocity.mean.end(), {made(f.centre(bin, 1)), 0.0});
    f.velocity.stderr_.insert(f.velocity.stderr_.end(), {se, se});
  }
  const auto j = poiseuille_fit(p, f);
  for (const char* half : {"lower_half", "upper_half"})
    EXPECT_NEAR(j[half]["viscosity"].get<double>(), eta, 1e-9) << half;
  EXPECT_NEAR(j["lower_half"]["wall_slip"].get<double>(), b_lower, 1e-9);
  EXPECT_NEAR(j["upper_half"]["wall_slip"].get<double>(), b_upper, 1e-9);
  for (const char* half : {"lower_half", "upper_half"}) {
    double variance = 0;
    const double base = j[half]["wall_slip"].get<double>(), step = 1e-6;
    for (int bin = 0; bin < 40; ++bin) {
      BinnedFields moved = f;
      moved.velocity.mean[2 * bin] += step;
      const double d = (poiseuille_fit(p, moved)[half]["wall_slip"].get<double>() - base) / step;
      variance += d * d * se * se;
    }
    EXPECT_NEAR(j[half]["wall_slip_stderr"].get<double>(), std::sqrt(variance),
                1e-4 * std::sqrt(variance))
        << half;
  }
  // Without walls (a periodic y) no slip is stated.
  p.walls[1] = WallPair{};
  EXPECT_FALSE(poiseuille_fit(p, f)["lower_half"].contains("wall_slip"));
}

// A field's errors carry its blocking factor (statistics::PooledBlocking): one bin whose x
// velocity runs 1, 1, 0, 0, 1, 1, 0, 0 over eight blocks (a memory of two blocks) has its block
// error raised to the error of pairs of blocks; y, constant, has none and keeps factor 1.
TEST(Diagnostics, FieldErrorsCarryTheBlockingFactor) {
  FieldSampler<2> sampler({{4, 4, 1}}, {{1, 1, 1}}, 8, 16, 1.0, 1.0);
  State<2> s;
  s.box = {{4, 4}};
  for (int i = 0; i < 3; ++i) {
    s.x[0].push_back(1 + i), s.x[1].push_back(2), s.id.push_back(i);
    s.v[0].push_back(0), s.v[1].push_back(0.5 * (i - 1));
  }
  for (int k = 0; k < 16; ++k) { // two samples per block
    for (double& v : s.v[0]) v = (k / 2) % 4 < 2 ? 1.0 : 0.0;
    sampler.sample(s);
  }
  const BinnedFields f = sampler.result();
  const double first = std::sqrt(8 * 0.25 / (7 * 8)), pairs = std::sqrt(4 * 0.25 / (3 * 4));
  EXPECT_DOUBLE_EQ(f.velocity.blocking_factor, pairs / first);
  EXPECT_NEAR(f.velocity.stderr_[0], pairs, 1e-15); // x: the pairs' error
  EXPECT_EQ(f.velocity.stderr_[1], 0.0);            // y: constant
  EXPECT_EQ(f.density.blocking_factor, 1.0);
}
