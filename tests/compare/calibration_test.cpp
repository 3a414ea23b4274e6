// The calibrated twin's walls on synthetic wall data whose answers are known exactly.

#include <gtest/gtest.h>

#include <cmath>

#include "compare/calibration.hpp"
#include "io/files.hpp"

using namespace twinflow;

namespace {

// A 2D cavity 10 x 10 of 1 x 1 bins, hot wall 1.5 at x = 0, cold 0.5 at x = 10, adiabatic
// no-slip walls in y; the fluid's T(x) = 1.3 - 0.06 x: it meets the walls at 1.3 and 0.7.
scene::SceneParameters cavity() {
  scene::SceneParameters s;
  s.dim = 2;
  s.box = {{10, 10, 1}};
  s.boundary[0] = {false, {{true, true}}, {{1.5, 0.5}}, true};
  s.boundary[1] = {false, {{false, false}}, {{1, 1}}, true};
  return s;
}

compare::BinnedState linear_fluid() {
  compare::BinnedState st;
  st.grid.dim = 2;
  st.grid.counts = {{10, 10, 1}};
  st.grid.spacing = {{1, 1, 1}};
  for (long b = 0; b < 100; ++b) {
    st.temperature.push_back(1.3 - 0.06 * (b % 10 + 0.5));
    st.temperature_se.push_back(0.01);
  }
  return st;
}

// The particle summary's wall results: heat flux into the fluid, its error, the friction.
io::Json wall_results(double q_hot, double q_cold) {
  io::Json r = io::Json::object();
  const auto wall = [&](const char* name, double q) {
    r["walls"][name]["heat_flux_in"] = q;
    r["walls"][name]["heat_flux_in_stderr"] = 0.001;
    r["walls"][name]["heat_flux_in_stderr_blocking"] = {0.001, 0.002, 0.0015};
    r["walls"][name]["friction_per_area"] = 1.0;
    r["walls"][name]["friction_depth"] = 0.5;
    r["walls"][name]["effective_position"] = 0.25;
  };
  wall("x_lower", q_hot);
  wall("x_upper", q_cold);
  wall("y_lower", 0.0);
  wall("y_upper", 0.0);
  return r;
}

// Compare parameters that extrapolate each wall's fluid temperature from the first two bin
// layers (no layer left out).
compare::CompareParameters without_wall_layer() {
  compare::CompareParameters c;
  c.wall_layer = 0;
  return c;
}

// The cavity's walls calibrated from hot and cold wall fluxes q_hot, q_cold.
compare::CalibratedWalls calibrate(const compare::CompareParameters& c,
                                   const compare::TwinFacts& twin, double q_hot = 0.1,
                                   double q_cold = -0.1) {
  return compare::calibrate_walls(wall_results(q_hot, q_cold), linear_fluid(), cavity(), c, twin);
}

} // namespace

TEST(Calibration, KapitzaConductanceIsTheWallFluxOverTheJump) {
  compare::CompareParameters c = without_wall_layer();
  const auto walls = calibrate(c, {true, false, 1.2});
  ASSERT_TRUE(walls.kapitza);
  // jumps 1.5 - 1.3 = 0.2 and 0.5 - 0.7 = -0.2
  EXPECT_NEAR(walls.wall[0][0].conductance, 0.1 / 0.2, 1e-12);
  EXPECT_NEAR(walls.wall[0][1].conductance, -0.1 / -0.2, 1e-12);
  EXPECT_GT(walls.wall[0][0].conductance_stderr, 0);
  // the adiabatic walls get no conductance, and no wall keeps the fluid's temperature
  EXPECT_EQ(walls.wall[1][0].conductance, 0);
  for (const auto& direction : walls.wall)
    for (const auto& w : direction) EXPECT_FALSE(std::isfinite(w.fluid_temperature));
  // Navier slip b = eta / zeta - (depth - plane) at every no-slip wall
  ASSERT_TRUE(walls.slip);
  for (int d = 0; d < 2; ++d)
    for (int side = 0; side < 2; ++side)
      EXPECT_NEAR(walls.wall[d][side].slip_length, 1.2 / 1.0 - 0.5, 1e-12);
}

TEST(Calibration, InverseLawTakesTheWallTemperatureSquared) {
  compare::CompareParameters c = without_wall_layer();
  c.wall_slip = false;
  const auto walls = calibrate(c, {true, true, 1.0});
  // q = h T_w^2 (1/T_f - 1/T_w)
  EXPECT_NEAR(walls.wall[0][0].conductance, 0.1 / (1.5 * 1.5 * (1 / 1.3 - 1 / 1.5)), 1e-12);
  EXPECT_FALSE(walls.slip);
}

TEST(Calibration, AJumpAgainstTheHeatFlowKeepsTheFluidsWallTemperature) {
  compare::CompareParameters c = without_wall_layer();
  // heat flowing out of the hot wall's fluid into the wall: no conductance can describe it
  const auto walls = calibrate(c, {true, false, 1.0}, -0.1, -0.1);
  EXPECT_EQ(walls.wall[0][0].conductance, 0);
  EXPECT_NEAR(walls.wall[0][0].fluid_temperature, 1.3, 1e-12);
  EXPECT_GT(walls.wall[0][1].conductance, 0);
}

TEST(Calibration, WallTemperaturesWithoutKapitzaAndALowMachTwin) {
  compare::CompareParameters c = without_wall_layer();
  const auto walls = calibrate(c, {false, false, 1.0});
  EXPECT_FALSE(walls.kapitza);
  EXPECT_FALSE(walls.slip); // Navier slip is a Boussinesq or compressible twin's
  EXPECT_EQ(walls.notes.size(), 1u);
  EXPECT_NEAR(walls.wall[0][0].fluid_temperature, 1.3, 1e-12);
  EXPECT_NEAR(walls.wall[0][1].fluid_temperature, 0.7, 1e-12);
  EXPECT_EQ(compare::calibration_description(c, {false, false, 1.0}),
            "walls at the fluid's wall temperatures");
}

TEST(Calibration, EffectiveWallsMoveInAndSpreadTheHeatFlowOverTheShorterWall) {
  compare::CompareParameters c = without_wall_layer();
  c.effective_walls = true;
  const auto walls = calibrate(c, {true, false, 1.2});
  EXPECT_TRUE(walls.effective_positions);
  EXPECT_EQ(walls.wall[0][0].position, 0.25);
  // the x walls are 10 long in the scene, 9.5 in the twin; the fluid met at x = 0.25
  const double q = 0.1 * 10 / 9.5, jump = 1.5 - (1.3 - 0.06 * 0.25);
  EXPECT_NEAR(walls.wall[0][0].conductance, q / jump, 1e-12);
  EXPECT_NEAR(walls.wall[0][0].slip_length, 1.2 / 1.0 - (0.5 - 0.25), 1e-12);
}

TEST(Calibration, AMissingMeasurementSaysWhatToDo) {
  compare::CompareParameters c;
  io::Json results = wall_results(0.1, -0.1);
  results["walls"]["y_lower"].erase("friction_per_area");
  try {
    compare::calibrate_walls(results, linear_fluid(), cavity(), c, {true, false, 1.0});
    FAIL() << "no error";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Compare/Wall slip = false"), std::string::npos);
  }
}
