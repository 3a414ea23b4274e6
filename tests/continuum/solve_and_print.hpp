#pragma once
// The continuum tests' report of a run: one line of results, the continuation steps, the mesh
// study (with a Richardson estimate from its last two changes) and the test properties.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "continuum/run.hpp"

namespace twinflow::continuum::test_cases {

inline std::string mesh_text(const std::array<unsigned, 3>& cells, int dim) {
  std::string text = std::to_string(cells[0]);
  for (int d = 1; d < dim; ++d) text += "x" + std::to_string(cells[d]);
  return text;
}

inline void print_result(const char* what, const ContinuumResult& r, double seconds) {
  const bool low_mach = r.model == "low-mach";
  std::printf("%s (%s, Ra = %g, epsilon = %g) on %s Q2: Nu = %.6f", what, r.model.c_str(),
              r.numbers.rayleigh, r.numbers.epsilon, mesh_text(r.cells, r.dim).c_str(), r.nusselt);
  if (r.walls.size() == 2)
    std::printf(" (walls %.6f, %.6f", r.walls[0].average, r.walls[1].average);
  if (r.consistent_wall_nusselt.size() == 2)
    std::printf("; consistent flux %.6f, %.6f", r.consistent_wall_nusselt[0],
                r.consistent_wall_nusselt[1]);
  if (r.walls.size() == 2) std::printf(")");
  if (r.has_midline_maxima)
    std::printf(", u_max = %.4f at y = %.4f, v_max = %.4f at x = %.4f",
                r.u_max_vertical_midline.value, r.u_max_vertical_midline.position,
                r.v_max_horizontal_midline.value, r.v_max_horizontal_midline.position);
  if (r.stream_function_max > 0)
    std::printf(", psi_max = %.4f at (%.4f, %.4f)", r.stream_function_max, r.vortex_centre[0],
                r.vortex_centre[1]);
  if (low_mach) std::printf(", P/p0 = %.6f, mass error %.1e", r.pressure_ratio, r.mass_error);
  std::printf(", %d Newton; %.1f s (assembly %.1f, solve %.1f)\n", r.newton_iterations, seconds,
              r.times.assembly, r.times.solve);
  if (!r.continuation_rayleigh.empty()) {
    std::printf("  continuation Ra:");
    for (const double ra : r.continuation_rayleigh) std::printf(" %g", ra);
    std::printf("\n");
  }
  for (const auto& m : r.mesh_study) {
    std::printf("  level %d: %s, %lu DoFs, Nu = %.6f, change %.2e", m.level,
                mesh_text(m.cells, r.dim).c_str(), m.dofs, m.nusselt, m.change_in_nusselt);
    if (low_mach) std::printf(", P/p0 = %.6f", m.pressure_ratio);
    std::printf(", %d Newton, %.2f s\n", m.newton_iterations, m.wall_time);
  }
  const std::size_t L = r.mesh_study.size();
  if (L >= 3) {
    // Richardson: the observed ratio q of successive changes, Nu + change / (q - 1).
    const double c1 = r.mesh_study[L - 2].change_in_nusselt,
                 c2 = r.mesh_study[L - 1].change_in_nusselt;
    const double q = c1 / c2;
    std::printf("  Richardson: change ratio %.2f, Nu extrapolated %.6f\n", q,
                r.nusselt + c2 / (q - 1));
  }
}

// run(p, "") with the report above; records nusselt (P/p0 for low-Mach) and the wall time.
inline ContinuumResult solve_and_print(const ContinuumParameters& p, const char* what) {
  const auto start = std::chrono::steady_clock::now();
  const ContinuumResult r = run(p, "");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  print_result(what, r, seconds);
  ::testing::Test::RecordProperty("nusselt", std::to_string(r.nusselt));
  if (r.model == "low-mach")
    ::testing::Test::RecordProperty("pressure_ratio", std::to_string(r.pressure_ratio));
  ::testing::Test::RecordProperty("wall_time_s", std::to_string(seconds));
  return r;
}

} // namespace twinflow::continuum::test_cases
