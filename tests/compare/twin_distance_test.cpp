// The comparison's numbers on hand-made states whose answers are known exactly.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "compare/twin_distance.hpp"
#include "io/files.hpp"

using namespace twinflow;

namespace {

io::Grid grid_2d(long nx, long ny, double h) {
  io::Grid g;
  g.dim = 2;
  g.counts = {{nx, ny, 1}};
  g.spacing = {{h, h, 1}};
  return g;
}

double centre(const io::Grid& g, int d, long b) {
  const long i = d == 0 ? b % g.counts[0] : b / g.counts[0];
  return (i + 0.5) * g.spacing[d];
}

// T(x, y) = a + s x everywhere, no flow; errors `se` per bin.
compare::BinnedState linear_state(const io::Grid& g, double a, double s, double se) {
  compare::BinnedState st;
  st.grid = g;
  for (long b = 0; b < g.cell_count(); ++b) {
    st.temperature.push_back(a + s * centre(g, 0, b));
    if (se > 0) st.temperature_se.push_back(se);
    for (int d = 0; d < 2; ++d) st.velocity.push_back(0);
    if (se > 0)
      for (int d = 0; d < 2; ++d) st.velocity_se.push_back(se);
  }
  return st;
}

} // namespace

TEST(TwinDistance, InteriorExcludesWholeBinsWithinTheWallLayer) {
  const io::Grid g = grid_2d(10, 10, 2.0);
  const auto layer = compare::interior_bins(g, {{true, true, false}}, 1.0);
  EXPECT_EQ(std::count(layer.begin(), layer.end(), 1), 64);
  const auto none = compare::interior_bins(g, {{true, true, false}}, 0.0);
  EXPECT_EQ(std::count(none.begin(), none.end(), 1), 100);
  const auto x_only = compare::interior_bins(g, {{true, false, false}}, 2.0); // exactly one bin
  EXPECT_EQ(std::count(x_only.begin(), x_only.end(), 1), 80);
  const auto thick = compare::interior_bins(g, {{true, true, false}}, 2.5);
  EXPECT_EQ(std::count(thick.begin(), thick.end(), 1), 36);
}

TEST(TwinDistance, ConstantOffsetGivesItsSizeAndIdenticalTwinsZero) {
  const io::Grid g = grid_2d(8, 6, 1.0);
  const auto interior = compare::interior_bins(g, {{true, true, false}}, 0.0);
  const auto c = linear_state(g, 1.0, 0.05, 0);
  const auto same = compare::temperature_distance(linear_state(g, 1.0, 0.05, 0), c, interior, 2.0);
  EXPECT_EQ(same.l2, 0.0);
  EXPECT_EQ(same.max, 0.0);
  const auto off = compare::temperature_distance(linear_state(g, 1.1, 0.05, 0), c, interior, 2.0);
  EXPECT_NEAR(off.l2, 0.05, 1e-14); // 0.1 / scale 2
  EXPECT_NEAR(off.max, 0.05, 1e-14);
  EXPECT_EQ(off.bins, 48);
}

// Pure noise of known sigma: l2 approaches the noise estimate, and the excess stays within a
// few of its own standard errors of zero.
TEST(TwinDistance, NoiseAloneIsRecognisedAsNoise) {
  const io::Grid g = grid_2d(40, 40, 1.0);
  const auto interior = compare::interior_bins(g, {{false, false, false}}, 0.0);
  const auto c = linear_state(g, 1.0, 0.0, 0);
  auto p = linear_state(g, 1.0, 0.0, 0.01);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 0.01);
  for (double& T : p.temperature) T += normal(rng);
  const auto d = compare::temperature_distance(p, c, interior, 1.0);
  EXPECT_NEAR(d.noise, 0.01, 1e-15);
  // mean of 1600 chi^2_1 / 1600: relative error sqrt(2/1600) = 3.5% on l2^2
  EXPECT_NEAR(d.l2 * d.l2 / (d.noise * d.noise), 1.0, 4 * std::sqrt(2.0 / 1600));
  EXPECT_LT(d.excess, 0.5 * d.noise);
}

// The twin's inputs' errors: a twin whose only difference from the particles is one input's
// response g (moved by +1 of its errors) sits exactly at the twin's error, noise_twin = |g|; the
// L2's error carries the response linearised (d . g); an offset five times the response is not
// explained by it. Responses read back from the continuum stage's file by input.
TEST(TwinDistance, TheTwinsInputsErrorsJoinTheParticleNoise) {
  const io::Grid g = grid_2d(6, 4, 1.0);
  const auto interior = compare::interior_bins(g, {{false, false, false}}, 0.0);
  const auto p = linear_state(g, 1.0, 0.05, 0.002);
  auto c = linear_state(g, 1.0, 0.05, 0);
  compare::BinnedState::Response r{"conductivity", {}, {}, {}};
  for (long b = 0; b < g.cell_count(); ++b) r.temperature.push_back(0.01 * (b % 2 ? 1 : -1));
  c.responses.push_back(r);
  for (long b = 0; b < g.cell_count(); ++b) c.temperature[b] -= r.temperature[b];
  const auto d = compare::temperature_distance(p, c, interior, 1.0);
  EXPECT_NEAR(d.noise, 0.002, 1e-15);
  EXPECT_NEAR(d.noise_twin, 0.01, 1e-15);
  EXPECT_NEAR(d.l2, 0.01, 1e-15);
  // var(mean d^2) = (4/n^2) (sum d^2 sigma^2 + (d . g)^2), d = g: l2_se = sqrt(sigma^2/n + g^2):
  // moved by one of its errors, the input would take the whole difference away (or double it)
  const double n = g.cell_count();
  EXPECT_NEAR(d.l2_stderr, std::sqrt(0.002 * 0.002 / n + 0.01 * 0.01), 1e-15);
  EXPECT_NEAR(d.to_json().at("noise_twin").get<double>(), 0.01, 1e-15);
  EXPECT_EQ(compare::temperature_distance(p, linear_state(g, 1.0, 0.05, 0), interior, 1.0)
                .to_json()
                .count("noise_twin"),
            0u); // no responses: the record as before

  const auto dir = std::filesystem::temp_directory_path() / "twinflow_twin_responses";
  std::filesystem::create_directories(dir);
  std::ofstream csv(dir / "coefficient_responses.csv");
  csv << "# comment\ninput,ix,iy,x_centre,y_centre,u_x,u_y,T\n";
  for (const char* input : {"conductivity", "viscosity"})
    for (long b = 0; b < g.cell_count(); ++b)
      csv << input << "," << b % 6 << "," << b / 6 << ",0,0," << 0.5 << "," << 0.25 << ","
          << (std::string(input) == "viscosity" ? 0.001 * b : 0.0) << "\n";
  csv.close();
  compare::BinnedState twin = linear_state(g, 1.0, 0.0, 0);
  compare::read_coefficient_responses(dir / "coefficient_responses.csv", twin);
  ASSERT_EQ(twin.responses.size(), 2u);
  EXPECT_EQ(twin.responses[1].input, "viscosity");
  EXPECT_DOUBLE_EQ(twin.responses[1].temperature[7], 0.007);
  EXPECT_DOUBLE_EQ(twin.responses[0].velocity[2 * 5 + 1], 0.25);
  compare::read_coefficient_responses(dir / "absent.csv", twin);
  EXPECT_TRUE(twin.responses.empty());
}

TEST(TwinDistance, WallTemperatureOfALinearProfileIsExact) {
  const io::Grid g = grid_2d(10, 10, 2.0);
  const auto interior = compare::interior_bins(g, {{true, true, false}}, 1.0);
  const auto p = linear_state(g, 0.9, -0.01, 0.003);
  const auto lower = compare::wall_fluid_temperature(p, interior, 0, 0);
  const auto upper = compare::wall_fluid_temperature(p, interior, 0, 1);
  EXPECT_NEAR(lower.value, 0.9, 1e-13);
  EXPECT_NEAR(upper.value, 0.9 - 0.01 * 20, 1e-13);
  EXPECT_DOUBLE_EQ(lower.extrapolated_from, 3.0); // bins [0, 2] are in the wall layer
  // 8 columns, each (1 + r)^2 + r^2 times sigma^2 with r = 1.5
  EXPECT_NEAR(lower.stderr_, 0.003 * std::sqrt(2.5 * 2.5 + 1.5 * 1.5) / std::sqrt(8.0), 1e-15);
}

// With the particle's blocks, a wall temperature's error is the spread of the same extrapolation
// over the blocks: a fluctuation shared by all bins of a block (a moving roll) counts in full,
// which the independent-bins formula divides by sqrt(columns). The stated error is the largest
// over 1, 2, 4 merged blocks. blocks.csv round trip included.
TEST(TwinDistance, WallTemperatureErrorFromTheBlocks) {
  const io::Grid g = grid_2d(10, 10, 2.0);
  const auto interior = compare::interior_bins(g, {{true, true, false}}, 1.0);
  auto p = linear_state(g, 0.9, -0.01, 0.003);
  const double a = 0.01; // block k: the whole field shifted by +a, -a, +a, ...
  const auto path = std::filesystem::temp_directory_path() / "twinflow_blocks.csv";
  {
    std::ofstream out(path);
    out << "# comment\nblock,bin,T_kinetic\n";
    for (int k = 0; k < 8; ++k)
      for (long b = 0; b < g.cell_count(); ++b)
        out << k << "," << b << "," << p.temperature[b] + (k % 2 ? -a : a) << "\n";
  }
  p.temperature_blocks = compare::read_temperature_blocks(g, path);
  ASSERT_EQ(p.temperature_blocks.size(), 8u);
  const auto w = compare::wall_fluid_temperature(p, interior, 0, 0);
  EXPECT_NEAR(w.value, 0.9, 1e-13);
  ASSERT_EQ(w.blocking.size(), 3u);                      // 8, 4, 2 blocks
  EXPECT_NEAR(w.blocking[0], a / std::sqrt(7.0), 1e-13); // sd of 8 values +-a, over sqrt(8)
  EXPECT_NEAR(w.blocking[1], 0, 1e-13);                  // merged pairs cancel
  EXPECT_DOUBLE_EQ(w.stderr_, w.blocking[0]);            // the largest
  {
    std::ofstream out(path);
    out << "block,bin,T_kinetic\n0,100,1.0\n"; // bin beyond the 10 x 10 grid
  }
  EXPECT_THROW(compare::read_temperature_blocks(g, path), io::InputError);
  std::filesystem::remove(path);
}

TEST(TwinDistance, VelocityDistanceIsTheVectorNorm) {
  const io::Grid g = grid_2d(4, 4, 1.0);
  const auto interior = compare::interior_bins(g, {{false, false, false}}, 0.0);
  auto p = linear_state(g, 1.0, 0.0, 0);
  const auto c = linear_state(g, 1.0, 0.0, 0);
  for (long b = 0; b < g.cell_count(); ++b) p.velocity[2 * b] = 0.03, p.velocity[2 * b + 1] = 0.04;
  const auto d = compare::velocity_distance(p, c, interior, 0.1);
  EXPECT_NEAR(d.l2, 0.5, 1e-14);
  EXPECT_NEAR(d.max, 0.5, 1e-14);
}

// A low-Mach twin's bins.csv carries the number density in a column "n": it is read, and its
// distance to the particles' density counts in units of the mean density; a twin without it
// has no density distance.
TEST(TwinDistance, DensityFromTheLowMachTwinsBins) {
  const io::Grid g = grid_2d(2, 2, 1.0);
  const auto path = std::filesystem::temp_directory_path() / "twinflow_density_bins.csv";
  {
    std::ofstream out(path);
    out << "ix,iy,x_centre,y_centre,u_x,u_y,p,T,n\n";
    for (long b = 0; b < 4; ++b)
      out << b % 2 << "," << b / 2 << ",0,0,0,0,0,1," << 2.0 + 0.1 * b << "\n";
  }
  const auto c = compare::continuum_state(g, path);
  ASSERT_EQ(c.density.size(), 4u);
  EXPECT_DOUBLE_EQ(c.density[3], 2.3);
  auto p = linear_state(g, 1.0, 0.0, 0);
  for (long b = 0; b < 4; ++b) p.density.push_back(2.0 + 0.1 * b + 0.04); // 2% of n0 = 2 above
  const auto interior = compare::interior_bins(g, {{false, false, false}}, 0.0);
  const auto d = compare::density_distance(p, c, interior, 2.0);
  EXPECT_NEAR(d.l2, 0.02, 1e-14);
  EXPECT_EQ(d.bins, 4);
  EXPECT_EQ(compare::density_distance(p, linear_state(g, 1.0, 0.0, 0), interior, 2.0).bins, 0);
  std::filesystem::remove(path);
}
