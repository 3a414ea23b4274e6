// The nominal twin's walls from the wall model (study/twin_wall_theory.hpp): its wall densities
// from its own bins, and the walls it moves in over pinned layers.
#include <cmath>

#include <gtest/gtest.h>

#include "continuum/twin_walls.hpp"
#include "study/twin_wall_theory.hpp"

namespace {

using twinflow::continuum::BinAverages;
using twinflow::study::wall_densities;

// n = a + b x + c y on 4 x 5 bins of 1 x 2: a linear field's extrapolation is exact.
TEST(TwinWallTheory, WallDensitiesExtrapolateTheTwinsBinsToEachWall) {
  const double a = 3, b = 0.25, c = -0.1;
  BinAverages bins;
  bins.bins = {{4, 5, 1}};
  bins.names = {"u_x", "u_y", "n", "T"};
  bins.values.assign(4, std::vector<double>(20, 0.0));
  for (int iy = 0; iy < 5; ++iy)
    for (int ix = 0; ix < 4; ++ix)
      bins.values[2][static_cast<std::size_t>(iy * 4 + ix)] = a + b * (ix + 0.5) + c * (2 * iy + 1);
  const auto n = wall_densities(bins, 2);
  EXPECT_NEAR(n[0][0], a + 5 * c, 1e-12);         // x = 0, mean over y
  EXPECT_NEAR(n[0][1], a + 4 * b + 5 * c, 1e-12); // x = 4
  EXPECT_NEAR(n[1][0], a + 2 * b, 1e-12);         // y = 0, mean over x
  EXPECT_NEAR(n[1][1], a + 2 * b + 10 * c, 1e-12);
  EXPECT_TRUE(std::isnan(n[2][0]));
}

TEST(TwinWallTheory, NoDensityFieldNoWallDensities) {
  BinAverages bins;
  bins.bins = {{2, 2, 1}};
  bins.names = {"u_x", "u_y", "p", "T"};
  bins.values.assign(4, std::vector<double>(4, 1.0));
  const auto n = wall_densities(bins, 2);
  EXPECT_TRUE(std::isnan(n[0][0]) && std::isnan(n[1][1]));
}

// The default cavity's walls as a slab (walls 1.5 / 0.5 along x, 20 apart, y periodic; the
// default fluid's D and pair part at T 0.9): the dense cold wall holds its layer (b ~ -0.34 rc,
// docs/theory.md "The wall layer"), so the twin's cold wall stands |b| inside the scene's plane
// with T = T_w and no Robin term, its slip reaching |b| further, its layer's particles out of the
// count; the hot wall keeps its plane and a Kapitza conductance. Taken twice (the fixed-point
// passes), nothing moves further.
TEST(TwinWallTheory, APinnedLayerMovesTheTwinsWallInByItsDepth) {
  twinflow::study::CaseParameters c;
  c.scene.dim = 2, c.scene.box = {{20, 20, 1}}, c.scene.density = 4, c.scene.temperature = 0.9;
  c.scene.boundary[0] = {false, {{true, true}}, {{1.5, 0.5}}, true};
  auto& p = c.particle;
  p.dim = 2, p.box = c.scene.box, p.density = 4, p.cv = 10, p.sigma = 3, p.kappa0 = 0.1;
  p.dissipation = {1.0, 2.0}, p.heat_weight = {1.0, 2.0};
  p.walls[0].present = true, p.walls[0].no_slip = true;
  p.walls[0].temperature = {{1.5, 0.5}}, p.walls[0].conduction = {{30, 30}};
  twinflow::transport::Coefficients k;
  k.diffusion = 0.3, k.diffusion_exponent = 1.36, k.state_density = 4, k.state_temperature = 0.9;
  k.conductivity_pair = 4.2;
  twinflow::continuum::ContinuumParameters twin;
  twin.dim = 2, twin.box = c.scene.box, twin.number_density = 4, twin.reference_temperature = 0.9;
  twin.model = twinflow::continuum::Model::Compressible;
  twin.conductivity = {20.0, 0.5};
  twin.boundary[0].periodic = false, twin.boundary[0].temperature = {{1.5, 0.5}};
  twin.boundary[0].slip_length = {{0.6, 0.3}};

  ASSERT_EQ(twinflow::study::take_wall_jumps(c, k, twin), 2);
  const auto& x = twin.boundary[0];
  const double depth = x.pinned_depth[1];
  EXPECT_GT(depth, 0.2);
  EXPECT_LT(depth, 0.5);
  EXPECT_EQ(x.pinned_depth[0], 0.0);
  EXPECT_GT(x.kapitza_conductance[0], 0.0);
  EXPECT_EQ(x.kapitza_conductance[1], 0.0);
  EXPECT_DOUBLE_EQ(twin.box[0], 20 - depth);
  EXPECT_DOUBLE_EQ(twin.bin_lower[0], 0.0);
  EXPECT_DOUBLE_EQ(twin.bin_extent(0), 20.0);
  EXPECT_DOUBLE_EQ(x.slip_length[1], 0.3 + depth);
  const double n_cold = c.scene.density_on_isobar(0.5);
  EXPECT_NEAR(twin.particle_count, 4 * 400 - n_cold * depth * 20, 1e-9);
  const auto moved = twinflow::continuum::moved_wall_distances(twin);
  EXPECT_NEAR(moved[1], depth, 1e-12);

  twinflow::study::take_wall_jumps(c, k, twin);
  EXPECT_DOUBLE_EQ(twin.box[0], 20 - depth);
  EXPECT_DOUBLE_EQ(twin.boundary[0].slip_length[1], 0.3 + depth);
}

} // namespace
