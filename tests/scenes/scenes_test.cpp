// The shipped scene cases, shrunk: what each reports is there and physically sound.
#include "scene_run.hpp"

using namespace twinflow::testing;

// Ideal DPDE fluid between thermal walls at T = 1.1: no potential, so the density is uniform and
// the force on each wall per area is the bulk pressure rho k T (000:(3.20)), T the fluid's.
TEST(Scenes, WallsEquilibriumPressureIsRhoKT) {
  const auto r = run_case("walls_equilibrium", "--threads 1");
  const double rho = 0.35355339;
  const double t = number(r, "T_internal"), t_se = number(r, "T_internal_stderr");
  for (const char* wall : {"walls.x_lower", "walls.x_upper"}) {
    const double p = number(r, std::string(wall) + ".pressure");
    const double se = std::hypot(number(r, std::string(wall) + ".pressure_stderr"), rho * t_se);
    EXPECT_LT(std::fabs(p - rho * t), 4 * se) << wall << ": " << p << " +- " << se;
  }
  EXPECT_NEAR(t, 1.1, 0.02) << "relaxes towards the walls' temperature";
}

// The relaxing temperature mode decays; the fit's chi is positive with a finite error, and
// the decay holds at the smaller box's faster rate.
TEST(Scenes, ThermalRelaxationFitsADecayRate) {
  const auto r = run_case("thermal_relaxation", "--threads 1 --set 'Scene/Box size=10, 5, 5' "
                                                "--set Particle/Steps=5000");
  const double chi = number(r, "relaxation.chi"), se = number(r, "relaxation.chi_stderr");
  EXPECT_GT(chi, 0.1);
  EXPECT_LT(chi, 0.5);
  EXPECT_GT(se, 0);
  EXPECT_LT(se, 0.2 * chi);
}
