// de Vahl Davis (1983) square cavity, Pr = 0.71, no-slip walls: average Nu (volume form) and the
// mid-line velocity maxima with their positions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cavity.hpp"
#include "solve_and_print.hpp"

using namespace twinflow::continuum;

namespace {

struct Reference {
  double rayleigh, nusselt, u_max, u_position, v_max, v_position;
};

// Velocities and positions: de Vahl Davis 1983, Table (benchmark solution); Nu: the issue's
// reference values (de Vahl Davis gives 1.118 and 2.243; these are the refined benchmarks).
const Reference kRa1e3{1e3, 1.1178, 3.649, 0.813, 3.697, 0.178};
const Reference kRa1e4{1e4, 2.2448, 16.178, 0.823, 19.617, 0.119};

void check_against(const Reference& ref, unsigned coarse, int refinements) {
  char what[32];
  std::snprintf(what, sizeof what, "Ra = %g", ref.rayleigh);
  const ContinuumResult r =
      test_cases::solve_and_print(test_cases::cavity(2, ref.rayleigh, coarse, refinements), what);
  // Nu: the Q2 volume-average Nu changes by < 1e-4 between the last two levels (printed mesh
  // study), so 0.1% measures the model, not the mesh.
  EXPECT_NEAR(r.nusselt, ref.nusselt, 1e-3 * ref.nusselt);
  // The wall-gradient Nu of both walls agrees with the volume form (flux balance) to 0.5%.
  ASSERT_EQ(r.walls.size(), 2u);
  for (const auto& w : r.walls) EXPECT_NEAR(w.average, r.nusselt, 5e-3 * r.nusselt);
  EXPECT_NEAR(r.u_max_vertical_midline.value, ref.u_max, 5e-3 * ref.u_max);
  EXPECT_NEAR(r.v_max_horizontal_midline.value, ref.v_max, 5e-3 * ref.v_max);
  // Positions: de Vahl Davis tabulates 3 digits from an interpolated 81x81 solution; +-0.005.
  EXPECT_NEAR(r.u_max_vertical_midline.position, ref.u_position, 5e-3);
  EXPECT_NEAR(r.v_max_horizontal_midline.position, ref.v_position, 5e-3);
}

} // namespace

TEST(DeVahlDavis, Rayleigh1e3) {
  check_against(kRa1e3, 8, 2);
}

TEST(DeVahlDavis, Rayleigh1e4) {
  check_against(kRa1e4, 8, 2);
}

TEST(DeVahlDavis, DimensionlessNumbersFromCoefficients) {
  // Particle-unit coefficients: Ra = g alpha dT H^3 / (nu chi), Pr = nu / chi, nu = eta/(n m),
  // chi = kappa/(n c_p).
  ContinuumParameters p = test_cases::cavity(2, 1e4, 4, 0);
  p.box = {{30, 30, 1}};
  p.number_density = 4, p.particle_mass = 1, p.heat_capacity = 10;
  p.viscosity = {2.0, 0.0}, p.conductivity = {40.0, -2.0};
  p.gravity = {{0, -0.01, 0}}, p.thermal_expansion = 0.5;
  const DimensionlessNumbers n = dimensionless_numbers(p);
  const double nu = 2.0 / 4.0, chi = 40.0 / 40.0;
  EXPECT_DOUBLE_EQ(n.kinematic_viscosity, nu);
  EXPECT_DOUBLE_EQ(n.thermal_diffusivity, chi);
  EXPECT_DOUBLE_EQ(n.prandtl, nu / chi);
  EXPECT_NEAR(n.rayleigh, 0.01 * 0.5 * 1.0 * 27000.0 / (nu * chi), 1e-9);
  EXPECT_EQ(n.heated_direction, 0);
  // Conduction flux with kappa = 40 (T/1)^-2 between 1.5 and 0.5: 40 (1/0.5 - 1/1.5) / 30.
  EXPECT_NEAR(n.conduction_flux, 40.0 * (2.0 - 2.0 / 3.0) / 30.0, 1e-12);
  set_rayleigh_prandtl(p, 1e5, 7.0);
  EXPECT_NEAR(dimensionless_numbers(p).rayleigh, 1e5, 1e-6);
  EXPECT_NEAR(dimensionless_numbers(p).prandtl, 7.0, 1e-12);
}
