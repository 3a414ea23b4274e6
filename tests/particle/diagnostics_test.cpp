// The diagnostics a scene creates (particle/diagnostics/diagnostics.hpp): only the ones it needs.
#include <gtest/gtest.h>

#include "helpers.hpp"
#include "particle/diagnostics/diagnostics.hpp"

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
