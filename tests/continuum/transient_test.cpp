// Boussinesq in time (BDF2, first step BDF1): the late-time state is the steady solution on the
// same mesh, the scheme is second order in time, and the 3D path reproduces 2D.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "cavity.hpp"
#include "continuum/boussinesq.hpp"
#include "continuum/run.hpp"

using namespace twinflow::continuum;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// u_x, u_y, T at a 7x7 grid of interior points of the unit cavity (z = Lz/2 in 3D).
template <int dim> std::vector<double> point_values(const BoussinesqProblem<dim>& problem) {
  std::vector<double> out;
  for (int i = 1; i <= 7; ++i)
    for (int j = 1; j <= 7; ++j) {
      dealii::Point<dim> x;
      x[0] = i / 8.0, x[1] = j / 8.0;
      if (dim == 3) x[2] = 0.125;
      const dealii::Vector<double> v = problem.value_at(x);
      out.push_back(v[0]);
      out.push_back(v[1]);
      out.push_back(v[dim + 1]);
    }
  return out;
}

double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

} // namespace

TEST(TransientCavity, LateTimeNusseltIsTheSteadyOne) {
  // de Vahl Davis Ra = 1e4, Pr = 0.71 on 16x16 Q2, from rest with the conduction profile. A
  // steady state of the discrete BDF2 equations is a steady discrete solution, so the late-time
  // Nu approaches the steady solver's on the same mesh; what is left at t = 1.5 (diffusion times
  // H^2/chi) is the decay of the transient: measured 4e-8 relative at t = 1 and < 1e-9 at
  // t = 1.5 (2e-16 at t = 3); bound 1e-6.
  const ContinuumParameters steady = test_cases::cavity(2, 1e4, 8, 1);
  const ContinuumResult r_steady = run(steady, "");
  const auto start = std::chrono::steady_clock::now();
  const ContinuumResult r = run(test_cases::in_time(steady, 1.5, 0.05), "");
  const double seconds = seconds_since(start);
  std::printf("Ra = 1e4, 16x16 Q2: steady Nu = %.8f; in time (dt = %g, %d steps, %.1f s): "
              "Nu(t = %g) = %.8f, rel. difference %.2e\n",
              r_steady.nusselt, r.time_step, r.time_steps, seconds, r.time, r.nusselt,
              std::abs(r.nusselt / r_steady.nusselt - 1));
  for (const auto& s : r.time_series)
    if (s.step % 5 == 0)
      std::printf("  t = %5.2f: Nu = %.8f, kinetic energy = %.6e, max speed = %.4f, %d Newton\n",
                  s.time, s.nusselt, s.kinetic_energy, s.max_speed, s.newton_iterations);
  ::testing::Test::RecordProperty("nusselt_transient", std::to_string(r.nusselt));
  ::testing::Test::RecordProperty("wall_time_s", std::to_string(seconds));
  EXPECT_NEAR(r.nusselt, r_steady.nusselt, 1e-6 * r_steady.nusselt);
  EXPECT_NEAR(r.u_max_vertical_midline.value, r_steady.u_max_vertical_midline.value,
              1e-6 * r_steady.u_max_vertical_midline.value);
  EXPECT_NEAR(r.v_max_horizontal_midline.value, r_steady.v_max_horizontal_midline.value,
              1e-6 * r_steady.v_max_horizontal_midline.value);
  // The series starts at rest with the conduction profile (Nu = 1) and records every step.
  ASSERT_EQ(r.time_series.size(), static_cast<std::size_t>(r.time_steps + 1));
  EXPECT_NEAR(r.time_series.front().nusselt, 1.0, 1e-10);
  EXPECT_EQ(r.time_series.front().kinetic_energy, 0.0);
  EXPECT_NEAR(r.time_series.back().max_speed, r.max_speed, 1e-12);
}

TEST(TransientCavity, SecondOrderInTime) {
  // Richardson: the same short transient (Ra = 1e4 from rest, t in [0, 0.1], where the flow
  // spins up) with dt, dt/2, dt/4, dt/8 on one 8x8 Q2 mesh; differences between successive
  // step sizes shrink by 2^p with the observed order p (BDF2: 2). Velocity and temperature at 49
  // interior points.
  const ContinuumParameters base = test_cases::cavity(2, 1e4, 8, 0);
  std::vector<std::vector<double>> values;
  const auto start = std::chrono::steady_clock::now();
  for (const int steps : {10, 20, 40, 80}) {
    BoussinesqProblem<2> problem(test_cases::in_time(base, 0.1, 0.1 / steps));
    problem.run("");
    values.push_back(point_values(problem));
  }
  std::vector<double> differences, orders;
  for (std::size_t k = 0; k + 1 < values.size(); ++k)
    differences.push_back(max_difference(values[k], values[k + 1]));
  for (std::size_t k = 0; k + 1 < differences.size(); ++k)
    orders.push_back(std::log2(differences[k] / differences[k + 1]));
  std::printf("BDF2, Ra = 1e4, t = 0.1 on 8x8 Q2 (%.1f s): max differences %.3e %.3e %.3e, "
              "observed orders %.3f %.3f\n",
              seconds_since(start), differences[0], differences[1], differences[2], orders[0],
              orders[1]);
  ::testing::Test::RecordProperty("observed_order", std::to_string(orders.back()));
  EXPECT_GT(orders.back(), 1.8);
  EXPECT_LT(orders.back(), 2.2);
}

TEST(TransientCavity, PeriodicInZReproduces2D) {
  // The 3D serial direct path in time on a box periodic in z: the z-independent 2D solution is
  // the 3D one at every step, so the time series agree to the Newton tolerance. A 4x4x2 mesh and
  // three steps (BDF1, then BDF2) keep the 3D assembly short.
  ContinuumParameters p3 = test_cases::in_time(test_cases::cavity(3, 1e4, 4, 0), 0.03, 0.01);
  p3.cells = {{4, 4, 2}};
  p3.linear_solver = LinearSolver::Direct;
  const ContinuumResult r3 = run(p3, "");
  const ContinuumResult r2 =
      run(test_cases::in_time(test_cases::cavity(2, 1e4, 4, 0), 0.03, 0.01), "");
  std::printf("direct 3D in time: %lu DoFs, %d steps, %.1f s (assembly %.1f, solve %.1f, "
              "postprocess %.1f s)\n",
              r3.dofs, r3.time_steps, r3.times.total(), r3.times.assembly, r3.times.solve,
              r3.times.postprocess);
  ASSERT_EQ(r3.time_series.size(), r2.time_series.size());
  for (std::size_t k = 0; k < r2.time_series.size(); ++k) {
    const auto &a = r3.time_series[k], &b = r2.time_series[k];
    std::printf("  t = %.2f: Nu 3D %.10f, 2D %.10f; max speed 3D %.8f, 2D %.8f\n", b.time,
                a.nusselt, b.nusselt, a.max_speed, b.max_speed);
    EXPECT_NEAR(a.nusselt, b.nusselt, 1e-7 * b.nusselt);
    EXPECT_NEAR(a.max_speed, b.max_speed, 1e-6 * std::max(b.max_speed, 1.0));
    // Kinetic energy: 3D integrates over the depth Lz = 0.25.
    EXPECT_NEAR(a.kinetic_energy, 0.25 * b.kinetic_energy, 1e-6 * b.kinetic_energy + 1e-14);
  }
}

TEST(TransientCavity, DistributedPathReproduces2D) {
  // p4est + Trilinos FGMRES in time on the same box: the linear solves stop at 1e-8 of the
  // residual, Newton at a relative update of 1e-9; the time series agree with 2D to 1e-6 (4x4x2
  // mesh, three steps).
  ContinuumParameters p3 = test_cases::in_time(test_cases::cavity(3, 1e4, 4, 0), 0.03, 0.01);
  p3.cells = {{4, 4, 2}};
  p3.linear_solver = LinearSolver::Iterative;
  const auto start = std::chrono::steady_clock::now();
  const ContinuumResult r3 = run(p3, "");
  const double seconds = seconds_since(start);
  const ContinuumResult r2 =
      run(test_cases::in_time(test_cases::cavity(2, 1e4, 4, 0), 0.03, 0.01), "");
  std::printf("distributed 3D in time: %lu DoFs, %d steps, %.1f s (assembly %.1f, solve %.1f, "
              "postprocess %.1f s)\n",
              r3.dofs, r3.time_steps, seconds, r3.times.assembly, r3.times.solve,
              r3.times.postprocess);
  ASSERT_EQ(r3.time_series.size(), r2.time_series.size());
  for (std::size_t k = 0; k < r2.time_series.size(); ++k) {
    const auto &a = r3.time_series[k], &b = r2.time_series[k];
    std::printf("  t = %.2f: Nu 3D %.10f, 2D %.10f\n", b.time, a.nusselt, b.nusselt);
    EXPECT_NEAR(a.nusselt, b.nusselt, 1e-6 * b.nusselt);
    EXPECT_NEAR(a.max_speed, b.max_speed, 1e-6 * std::max(b.max_speed, 1.0));
  }
  EXPECT_TRUE(r3.has_midline_maxima);
  EXPECT_NEAR(r3.u_max_vertical_midline.value, r2.u_max_vertical_midline.value,
              1e-5 * r2.u_max_vertical_midline.value);
  EXPECT_NEAR(r3.v_max_horizontal_midline.value, r2.v_max_horizontal_midline.value,
              1e-5 * r2.v_max_horizontal_midline.value);
}
