// Variants of the cavity: free-slip walls (no literature value: mesh convergence) and a 3D box
// periodic in z that must reproduce the 2D cavity.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cavity.hpp"
#include "solve_and_print.hpp"

using namespace twinflow::continuum;
using test_cases::solve_and_print;

TEST(FreeSlipCavity, ConvergesUnderRefinement) {
  // Free slip on all four walls (no-normal-flux constraints, symmetric-gradient viscous term).
  // No literature value: the mesh study must converge. Measured changes fall by ~25x per level
  // (h^4-h^5), so the last change bounds the error; require < 1e-4 relative on the finest mesh
  // (32x32 at Ra = 1e3, 64x64 at Ra = 1e4).
  for (const double rayleigh : {1e3, 1e4}) {
    char label[64];
    std::snprintf(label, sizeof label, "free slip Ra = %g", rayleigh);
    const ContinuumResult r = solve_and_print(
        test_cases::cavity(2, rayleigh, 8, rayleigh < 5e3 ? 2 : 3, /*no_slip=*/false), label);
    const auto& last = r.mesh_study.back();
    EXPECT_LT(std::abs(last.change_in_nusselt), 1e-4 * last.nusselt);
    // Free slip offers less resistance than no slip: more heat transfer than de Vahl Davis.
    EXPECT_GT(r.nusselt, rayleigh == 1e3 ? 1.1178 : 2.2448);
    // Flux balance: both walls carry the volume-average heat flux. The wall gradient converges
    // only like h^2 where the free-slip jet hits the corners (1% off on 32x32 at Ra = 1e4), so
    // the bound is 1%.
    for (const auto& w : r.walls) {
      std::printf("  wall %d/%d: Nu = %.6f\n", w.direction, w.side, w.average);
      EXPECT_NEAR(w.average, r.nusselt, 1e-2 * r.nusselt);
    }
  }
}

TEST(Cavity3D, PeriodicInZReproduces2D) {
  // The 3D discrete space contains the z-independent 2D solution, which is therefore the 3D
  // solution: Nu agrees with 2D on the same xy mesh to the Newton tolerance (bound 1e-6), and
  // with the de Vahl Davis value 2.2448 to 0.1% (16x16 Q2: 2D Nu is 2.24459, docs/build.md).
  const double rayleigh = 1e4;
  ContinuumParameters p3 = test_cases::cavity(3, rayleigh, 8, 1);
  p3.cells = {{8, 8, 1}}; // z: one cell, kept through the refinement (a thin slice)
  p3.linear_solver = LinearSolver::Direct;
  const ContinuumResult r3 = solve_and_print(p3, "3D periodic z, direct");
  const ContinuumResult r2 = solve_and_print(test_cases::cavity(2, rayleigh, 8, 1), "2D");
  EXPECT_NEAR(r3.nusselt, r2.nusselt, 1e-6 * r2.nusselt);
  EXPECT_NEAR(r3.nusselt, 2.2448, 1e-3 * 2.2448);
  EXPECT_NEAR(r3.u_max_vertical_midline.value, r2.u_max_vertical_midline.value, 1e-5 * 16);
  EXPECT_NEAR(r3.v_max_horizontal_midline.value, r2.v_max_horizontal_midline.value, 1e-5 * 20);
}

TEST(Cavity3D, IterativeDistributedPathReproduces2D) {
  // p4est + Trilinos FGMRES (block-triangular AMG preconditioner) on the same problem: the
  // linear solves stop at 1e-8 of the residual and Newton at a relative update of 1e-9, so Nu
  // agrees with the 2D direct solve to 1e-6.
  const double rayleigh = 1e4;
  ContinuumParameters p3 = test_cases::cavity(3, rayleigh, 8, 1);
  p3.cells = {{8, 8, 1}};
  p3.linear_solver = LinearSolver::Iterative;
  const ContinuumResult r3 = solve_and_print(p3, "3D periodic z, iterative");
  const ContinuumResult r2 = run(test_cases::cavity(2, rayleigh, 8, 1), "");
  EXPECT_NEAR(r3.nusselt, r2.nusselt, 1e-6 * r2.nusselt);
  ASSERT_EQ(r3.walls.size(), 2u);
  EXPECT_NEAR(r3.walls[0].average, r2.walls[0].average, 1e-6 * r2.nusselt);
  // Mid-line maxima (shared post-processing, point values across processes).
  ASSERT_TRUE(r3.has_midline_maxima);
  EXPECT_NEAR(r3.u_max_vertical_midline.value, r2.u_max_vertical_midline.value, 1e-5 * 16);
  EXPECT_NEAR(r3.u_max_vertical_midline.position, r2.u_max_vertical_midline.position, 1e-6);
  EXPECT_NEAR(r3.v_max_horizontal_midline.value, r2.v_max_horizontal_midline.value, 1e-5 * 20);
  EXPECT_NEAR(r3.v_max_horizontal_midline.position, r2.v_max_horizontal_midline.position, 1e-6);
}

// Kapitza (Robin) walls, q = h (T_wall - T). Without gravity the steady state is conduction in
// series through the two wall conductances and the layer: q = dT / (1/h_0 + H/kappa + 1/h_1),
// exact for Q2 (linear T). With convection, h -> infinity gives back the Dirichlet cavity.
TEST(KapitzaWalls, ConductionInSeriesIsExactAndLargeConductanceIsDirichlet) {
  ContinuumParameters p = test_cases::cavity(2, 1e4, 8, 1);
  p.gravity = {{0, 0, 0}};
  p.boundary[0].kapitza_conductance = {{2.0, 4.0}};
  const ContinuumResult r = run(p, "");
  const double kappa = p.conductivity.value_at_reference;   // 1 in these units
  const double q = 1.0 / (1 / 2.0 + 1.0 / kappa + 1 / 4.0); // dT = 1, H = 1
  EXPECT_NEAR(r.nusselt, q / kappa, 1e-8);
  // fluid temperatures at the walls: T_wall -+ q / h
  EXPECT_NEAR(r.temperature_max, 1.5 - q / 2.0, 1e-8);
  EXPECT_NEAR(r.temperature_min, 0.5 + q / 4.0, 1e-8);

  ContinuumParameters dirichlet = test_cases::cavity(2, 1e4, 8, 1);
  ContinuumParameters stiff = dirichlet;
  stiff.boundary[0].kapitza_conductance = {{1e9, 1e9}};
  const double nu_dirichlet = run(dirichlet, "").nusselt, nu_stiff = run(stiff, "").nusselt;
  std::printf("Nu: Dirichlet %.8f, h = 1e9 %.8f\n", nu_dirichlet, nu_stiff);
  EXPECT_NEAR(nu_stiff, nu_dirichlet, 1e-6 * nu_dirichlet);
}

// The inverse law, q = h T_w^2 (1/T - 1/T_w): in series without gravity the layer's end
// temperatures T_0, T_1 solve q = h_0 T_w0^2 (1/T_0 - 1/T_w0) = kappa (T_0 - T_1) / H =
// h_1 T_w1^2 (1/T_w1 - 1/T_1) (exact for Q2: linear T). Found here by bisection on T_0; the
// Newton solve must reproduce it, which checks the boundary residual and its Jacobian.
TEST(KapitzaWalls, InverseLawInSeriesIsExact) {
  ContinuumParameters p = test_cases::cavity(2, 1e4, 8, 1);
  p.gravity = {{0, 0, 0}};
  p.boundary[0].kapitza_conductance = {{2.0, 4.0}};
  p.boundary[0].kapitza_inverse = true;
  const ContinuumResult r = run(p, "");
  const double kappa = p.conductivity.value_at_reference, Tw0 = 1.5, Tw1 = 0.5;
  const auto cold_end = [&](double q) { return 1 / (1 / Tw1 - q / (4.0 * Tw1 * Tw1)); };
  double lo = Tw1, hi = Tw0; // T_0: the hot wall's flux minus the layer's changes sign once
  for (int k = 0; k < 200; ++k) {
    const double T0 = 0.5 * (lo + hi), q = 2.0 * Tw0 * Tw0 * (1 / T0 - 1 / Tw0);
    (kappa * (T0 - cold_end(q)) > q ? hi : lo) = T0;
  }
  const double T0 = 0.5 * (lo + hi), q = 2.0 * Tw0 * Tw0 * (1 / T0 - 1 / Tw0);
  EXPECT_NEAR(r.nusselt, q / kappa, 1e-8);
  EXPECT_NEAR(r.temperature_max, T0, 1e-8);
  EXPECT_NEAR(r.temperature_min, cold_end(q), 1e-8);
}

// Navier slip against the exact plane Poiseuille flow with slip: walls at y = 0 and 1 with slip
// length b, x periodic, a uniform body force f = n m alpha (T - T_ref) |g| (both walls at T, so T
// is uniform): u(y) = f / (2 eta) (y (1 - y) + b) (Navier 1823), whose quadratic Q2 holds
// exactly, so u_max = f / (2 eta) (1/4 + b) to the solver's tolerance. b -> 0 is no slip.
TEST(NavierSlip, PoiseuilleWithSlipIsExact) {
  for (const double b : {0.0, 0.1, 1.0}) {
    ContinuumParameters p;
    p.dim = 2;
    p.model = Model::Boussinesq;
    p.box = {{1.0, 1.0, 1.0}};
    p.cells = {{2, 4, 1}};
    p.refinements = 1;
    p.reference_temperature = 1.0;
    p.thermal_expansion = 1.0;
    p.viscosity = {0.5, 0.0};
    p.boundary[0] = {true, {{false, false}}, {{1, 1}}, {{0, 0}}, true};    // periodic x
    p.boundary[1] = {false, {{true, true}}, {{1.5, 1.5}}, {{0, 0}}, true}; // walls, T = 1.5
    p.boundary[1].slip_length = {{b, b}};
    p.boundary[2].periodic = true;
    p.gravity = {{-2.0, 0, 0}}; // f = n m alpha (T - T_ref) |g| = 1 along +x
    p.bins = {{1, 4, 1}};
    p.write_fields = false;
    const ContinuumResult r = run(p, "");
    const double f = 1.0, eta = 0.5, expected = f / (2 * eta) * (0.25 + b);
    // u_max on the vertical mid-line, in units of chi / H (chi = kappa / (n c_p) = 1, H = 1)
    EXPECT_NEAR(r.u_max_vertical_midline.value, expected, 1e-7) << "b = " << b;
    EXPECT_NEAR(r.u_max_vertical_midline.position, 0.5, 1e-3) << "b = " << b;
  }
}

// Kinetic slip (references.md, "Kinetic slip at a particle wall") in the same flow: walls at T_w =
// 1.5, conduction strong enough (kappa 1e6) that T and so n stay uniform under the compressible
// twin's viscous heating, so the wall friction beta = 2 n [sqrt(m T / 2 pi) + rho_w I gamma(T,
// T_w)] is uniform and the flow is Poiseuille's with slip length eta / beta, here from the
// formula written out. The compressible twin's n enters beta (its density field).
TEST(NavierSlip, KineticSlipIsNavierWithEtaOverBeta) {
  for (const Model model : {Model::Boussinesq, Model::Compressible}) {
    ContinuumParameters p;
    p.dim = 2;
    p.model = model;
    p.box = {{1.0, 1.0, 1.0}};
    p.cells = {{2, 4, 1}};
    p.refinements = 1;
    p.number_density = 4.0;
    p.heat_capacity = 13.0;
    p.reference_temperature = 1.0;
    p.thermal_expansion = 1.0;
    p.viscosity = {0.5, 0.0};
    p.conductivity = {1e6, 0.0};
    p.boundary[0] = {true, {{false, false}}, {{1, 1}}, {{0, 0}}, true};    // periodic x
    p.boundary[1] = {false, {{true, true}}, {{1.5, 1.5}}, {{0, 0}}, true}; // walls, T = 1.5
    p.boundary[1].kinetic_slip = {{true, true}};
    p.wall_friction = {4.0, 1.0 / 45, 0.0, 2.25}; // rho_w, I_2 (s = 2), sigma^2 / 4 (sigma = 3)
    p.boundary[2].periodic = true;
    // the body force along +x: Boussinesq n m alpha (T - T_ref) |g| = 4, compressible m n g = 1
    const bool boussinesq = model == Model::Boussinesq;
    p.gravity = {{boussinesq ? -2.0 : 0.25, 0, 0}};
    const double f = boussinesq ? 4.0 : 1.0;
    p.bins = {{1, 4, 1}};
    p.write_fields = false;
    const ContinuumResult r = run(p, "");
    const double T = 1.5, gamma = 9.0 / (2 * T), eta = 0.5; // gamma(T, T) = sigma^2 / 2T
    const double beta = 2 * 4.0 * (std::sqrt(T / (2 * M_PI)) + 4.0 / 45 * gamma);
    const double b = eta / beta, expected = f / (2 * eta) * (0.25 + b);
    const double chi = 1e6 / (4.0 * 13.0); // u_max is reported in units of chi / H, H = 1
    const double u_max = r.u_max_vertical_midline.value * chi;
    std::printf("%s: kinetic slip length %.5f rc, u_max %.8f, exact %.8f\n",
                boussinesq ? "Boussinesq" : "compressible", b, u_max, expected);
    EXPECT_NEAR(u_max, expected, 1e-6 * expected);
  }
}
