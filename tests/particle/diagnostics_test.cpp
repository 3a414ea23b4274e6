// The diagnostics a scene creates (particle/diagnostics/diagnostics.hpp): only the ones it needs.
#include <gtest/gtest.h>

#include "helpers.hpp"
#include "particle/diagnostics/diagnostics.hpp"
#include "particle/diagnostics/plugins.hpp"

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
