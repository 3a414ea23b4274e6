// Le Quere et al. (2005) low-Mach cavity at Ra = 1e5 and 1e6, epsilon = 0.6, Pr = 0.71, constant
// properties and Sutherland's law (label validation: minutes each).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "continuum/run.hpp"
#include "low_mach_cavity.hpp"

using namespace twinflow::continuum;

namespace {

ContinuumResult solve_and_print(const ContinuumParameters& p, const char* what) {
  const auto start = std::chrono::steady_clock::now();
  const ContinuumResult r = run(p, "");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s (Ra = %g, epsilon = %g) on %ux%u Q2: Nu = %.6f (wall gradient %.6f, %.6f; "
              "consistent flux %.6f, %.6f), P/p0 = %.6f, %d Newton; %.1f s (assembly %.1f, "
              "solve %.1f)\n",
              what, r.numbers.rayleigh, r.numbers.epsilon, r.cells[0], r.cells[1], r.nusselt,
              r.walls[0].average, r.walls[1].average, r.consistent_wall_nusselt[0],
              r.consistent_wall_nusselt[1], r.pressure_ratio, r.newton_iterations, seconds,
              r.times.assembly, r.times.solve);
  std::printf("  continuation Ra:");
  for (const double ra : r.continuation_rayleigh) std::printf(" %g", ra);
  std::printf("\n");
  for (const auto& m : r.mesh_study)
    std::printf("  level %d: %ux%u, Nu = %.6f, change %.2e, %d Newton, %.2f s\n", m.level,
                m.cells[0], m.cells[1], m.nusselt, m.change_in_nusselt, m.newton_iterations,
                m.wall_time);
  const std::size_t L = r.mesh_study.size();
  if (L >= 3) {
    // Richardson: the observed ratio q of successive changes, Nu + change / (q - 1).
    const double c1 = r.mesh_study[L - 2].change_in_nusselt,
                 c2 = r.mesh_study[L - 1].change_in_nusselt;
    const double q = c1 / c2;
    std::printf("  Richardson: change ratio %.2f, Nu extrapolated %.6f\n", q,
                r.nusselt + c2 / (q - 1));
  }
  ::testing::Test::RecordProperty("nusselt", std::to_string(r.nusselt));
  ::testing::Test::RecordProperty("pressure_ratio", std::to_string(r.pressure_ratio));
  ::testing::Test::RecordProperty("wall_time_s", std::to_string(seconds));
  return r;
}

// Reference values: the paper's own table (Le Quere et al. 2005, Part 1, reference solutions for
// Ra = 1e6 and 1e7) could not be retrieved by this project (not in the searchable corpora; the
// later papers found cite it without tabulating the values). The one number below, Nu = 8.8598
// for constant properties at Ra = 1e6, is the value quoted in issue 9 (its search hint) and is
// checked as such: source table NOT verified. No P/p0 and no Sutherland reference is asserted;
// those runs check mesh convergence and flux consistency only, and print their values.
void check_le_quere(const ContinuumResult& r) {
  const auto& study = r.mesh_study;
  ASSERT_GE(study.size(), 2u);
  // 128x128 Q2: the last refinement changes Nu by < 0.3% (the changes fall ~8x per level).
  EXPECT_LT(std::abs(study.back().change_in_nusselt), 3e-3 * r.nusselt);
  // The consistent fluxes through the hot and the cold wall agree with the volume Nu.
  for (const double wall : r.consistent_wall_nusselt)
    EXPECT_NEAR(wall, r.nusselt, 2e-3 * r.nusselt);
  EXPECT_LT(std::abs(r.mass_error), 1e-12);
}

} // namespace

TEST(LowMachValidation, LeQuereRayleigh1e6Constant) {
  const ContinuumResult r =
      solve_and_print(test_cases::low_mach_cavity(1e6, 0.6, false, 16, 3), "constant");
  check_le_quere(r);
  // 128x128: Nu = 8.85971 (last change 1.0e-3, falling 16x per level: Richardson 8.85978),
  // P/p0 = 0.856343 (Richardson 0.856338).
  EXPECT_NEAR(r.nusselt, 8.8598, 2e-4 * 8.8598); // issue 9's value, table not verified
}

TEST(LowMachValidation, LeQuereRayleigh1e6Sutherland) {
  // 128x128: Nu = 8.68576 (last change 7.8e-3, falling 8.5x per level: Richardson 8.6868),
  // P/p0 = 0.924547 (Richardson 0.92447); printed, not asserted against a reference.
  const ContinuumResult r =
      solve_and_print(test_cases::low_mach_cavity(1e6, 0.6, true, 16, 3), "Sutherland");
  check_le_quere(r);
}
