// The nominal twin's wall densities from its own bins (study/twin_wall_theory.hpp).
#include <cmath>

#include <gtest/gtest.h>

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

} // namespace
