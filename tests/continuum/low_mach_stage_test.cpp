// `twinflow continuum` with the low-Mach case file, end to end: dispatch on Model = low-mach,
// printed Ra, Pr, epsilon, summary.json with P/p0, fields (including the density n).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>

#include "../run_twinflow.hpp"
#include "io/files.hpp"
#include "io/json.hpp"

namespace fs = std::filesystem;
using twinflow::io::Json;
using twinflow::testing::Result;
using twinflow::testing::run_twinflow;

TEST(LowMachStage, CaseFileEndToEnd) {
  // The shipped case shrunk to 16x16 (one refinement of 8x8).
  const fs::path out = twinflow::testing::fresh_dir("low_mach_stage_test", "cavity");
  const std::string case_file =
      std::string(TWINFLOW_SOURCE_DIR) + "/cases/continuum_low_mach_cavity_2d.prm";
  const Result r =
      run_twinflow("continuum " + case_file + " --out " + out.string() +
                   " --set 'Continuum/Mesh/Refinements=1' --set 'Scene/Field bins=16'");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("low-Mach, steady, 2D, Ra = 100000, Pr = 0.71, epsilon = 0.6"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("P/p0 = "), std::string::npos) << r.output;
  for (const char* f : {"summary.json", "fields.h5", "fields.xdmf", "bins.csv", "wall_nusselt.csv"})
    EXPECT_TRUE(fs::exists(out / "continuum" / f)) << f;
  const Json summary = twinflow::io::read_json(out / "continuum" / "summary.json");
  const Json* results = twinflow::io::find(summary, {"results"});
  ASSERT_NE(results, nullptr);
  EXPECT_EQ(twinflow::io::find(summary, {"continuum_parameters", "model"})->get<std::string>(),
            "low-mach");
  EXPECT_NEAR(twinflow::io::find(summary, {"dimensionless", "rayleigh"})->get<double>(), 1e5, 1e-6);
  EXPECT_NEAR(twinflow::io::find(summary, {"dimensionless", "epsilon"})->get<double>(), 0.6, 1e-12);
  // 16x16 values of this solver (regression; 64x64: Nu = 4.5516, P/p0 = 0.8518, case header).
  EXPECT_NEAR(twinflow::io::find(*results, {"nusselt_volume_average"})->get<double>(), 4.53877,
              1e-4);
  EXPECT_NEAR(twinflow::io::find(*results, {"pressure_ratio_P_over_p0"})->get<double>(), 0.853259,
              1e-5);
  EXPECT_LT(std::abs(twinflow::io::find(*results, {"relative_mass_error"})->get<double>()), 1e-12);
  // The bins carry n(P, T); over the 16 x 16 bins, one per cell, its mean is the mean density 1
  // (mass conservation). The solver conserves mass in its 3-point Gauss rule, the bins integrate
  // on a 6x finer one: they differ by that rule's error for n = P/T on this mesh (6e-6).
  const std::string bins = twinflow::io::read_file(out / "continuum" / "bins.csv");
  std::istringstream lines(bins);
  std::string line;
  std::getline(lines, line);
  ASSERT_EQ(line.substr(line.size() - 2), ",n") << line;
  double sum = 0;
  int count = 0;
  while (std::getline(lines, line)) sum += std::stod(line.substr(line.rfind(',') + 1)), ++count;
  EXPECT_EQ(count, 256);
  EXPECT_NEAR(sum / count, 1.0, 1e-5);
}

// The same cavity as a thin periodic slice of a 3D box (tests/continuum/thin_low_mach.prm: y
// periodic, 4 deep, one coarse cell across, which refinement keeps): the flow is uniform along
// y, so the solution is the 2D one above, to the solvers' tolerance.
TEST(LowMachStage, ThinPeriodicSliceIsTheTwoDimensionalCavity) {
  const fs::path out = twinflow::testing::fresh_dir("low_mach_stage_test", "thin");
  const std::string case_file =
      std::string(TWINFLOW_SOURCE_DIR) + "/tests/continuum/thin_low_mach.prm";
  const Result r = run_twinflow("continuum " + case_file + " --out " + out.string() +
                                " --set 'Continuum/Mesh/Refinements=1'");
  ASSERT_EQ(r.code, 0) << r.output;
  const Json summary = twinflow::io::read_json(out / "continuum" / "summary.json");
  const Json* results = twinflow::io::find(summary, {"results"});
  ASSERT_NE(results, nullptr);
  const auto& cells = (*twinflow::io::find(summary, {"mesh", "cells"}));
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[0].get<double>(), 16);
  EXPECT_EQ(cells[1].get<double>(), 1);
  EXPECT_EQ(cells[2].get<double>(), 16);
  EXPECT_NEAR(twinflow::io::find(*results, {"nusselt_volume_average"})->get<double>(), 4.53877,
              1e-4);
  EXPECT_NEAR(twinflow::io::find(*results, {"pressure_ratio_P_over_p0"})->get<double>(), 0.853259,
              1e-5);
}

// Free-slip walls around a thin periodic slice: no wall holds the velocity along the slice, so
// the solvers pin its translation; the slice then gives the 2D free-slip cavity again.
TEST(LowMachStage, FreeSlipThinSliceIsTheTwoDimensionalCavity) {
  const std::string slip = " --set 'Continuum/Mesh/Refinements=0' --set 'Scene/x "
                           "boundaries/Slip=free-slip'";
  auto nusselt = [&](const std::string& case_file, const char* other_walls, const char* dir) {
    const fs::path out = twinflow::testing::fresh_dir("low_mach_stage_test", dir);
    const Result r = run_twinflow("continuum " + case_file + " --out " + out.string() + slip +
                                  " --set 'Scene/" + other_walls + " boundaries/Slip=free-slip'");
    EXPECT_EQ(r.code, 0) << r.output;
    const Json summary = twinflow::io::read_json(out / "continuum" / "summary.json");
    return twinflow::io::find(summary, {"results", "nusselt_volume_average"})->get<double>();
  };
  const std::string source = TWINFLOW_SOURCE_DIR;
  const double nu_2d = nusselt(source + "/cases/continuum_low_mach_cavity_2d.prm", "y", "slip_2d");
  const double nu_thin = nusselt(source + "/tests/continuum/thin_low_mach.prm", "z", "slip_thin");
  EXPECT_NEAR(nu_thin, nu_2d, 1e-6 * nu_2d);
}

// Continuum/Model = auto picks the compressible twin for the default cavity (g H / c^2 = 0.4 >
// 0.1) and says why; its bins carry n; bad input exits 2 with one line and writes nothing.
TEST(CompressibleStage, AutoPicksCompressibleAndBadInputExits2) {
  const fs::path out = twinflow::testing::fresh_dir("compressible_stage_test", "cavity");
  const std::string case_file = std::string(TWINFLOW_SOURCE_DIR) + "/cases/heated_cavity_2d.prm";
  const std::string base = "continuum " + case_file + " --set Continuum/Model=auto" +
                           " --set 'Continuum/Coefficients/Heat capacity=13'";
  const Result r = run_twinflow(base + " --out " + out.string() +
                                " --set 'Continuum/Mesh/Refinements=0' --set 'Scene/Field bins=8'");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("Model = auto: compressible (stratification g H / c^2 0.4 > 0.1)"),
            std::string::npos)
      << r.output;
  const Json summary = twinflow::io::read_json(out / "continuum" / "summary.json");
  EXPECT_EQ(twinflow::io::find(summary, {"continuum_parameters", "model"})->get<std::string>(),
            "compressible");
  EXPECT_LT(
      std::abs(twinflow::io::find(summary, {"results", "relative_mass_error"})->get<double>()),
      1e-12);
  const std::string bins = twinflow::io::read_file(out / "continuum" / "bins.csv");
  EXPECT_NE(bins.substr(0, bins.find('\n')).find(",n,"), std::string::npos) << bins;
  for (const std::string& bad :
       {std::string("--set 'Continuum/Coefficients/Bulk viscosity=-1'"),
        std::string("--set 'Continuum/Mesh/Refinements=0' --set 'Scene/Gravity=0, -0.2'"),
        // dp/dn = T + 2 n B < 0 at the cold wall (0.5) from n = 0.5 / (2 * 0.2) = 1.25 < 3 n0
        std::string("--set 'Continuum/Coefficients/Excess pressure=-0.2, 0, 0'"),
        std::string("--set Continuum/Model=low-mach "
                    "--set 'Continuum/Coefficients/Excess pressure=0.5, 0, 0'")}) {
    const fs::path none = twinflow::testing::fresh_dir("compressible_stage_test", "bad");
    const Result e = run_twinflow(base + " --out " + none.string() + " " + bad);
    EXPECT_EQ(e.code, 2) << e.output;
    EXPECT_EQ(std::count(e.output.begin(), e.output.end(), '\n'), 1) << e.output;
    EXPECT_FALSE(fs::exists(none / "continuum")) << bad;
    std::printf("  %s: %s", bad.c_str(), e.output.c_str());
  }
}

// Where the walls' epsilon alone would pick low-Mach, a fluid with a conservative force gets the
// compressible twin (the low-Mach twin's p = n k T would leave its excess pressure out), and auto
// says so; without the force, low-Mach.
TEST(CompressibleStage, AutoPicksCompressibleForAConservativeForce) {
  const std::string case_file =
      std::string(TWINFLOW_SOURCE_DIR) + "/cases/conduction_column_repulsive_2d.prm";
  for (const bool force : {true, false}) {
    const fs::path out = twinflow::testing::fresh_dir("compressible_stage_test", "auto_force");
    const Result r = run_twinflow("continuum " + case_file + " --out " + out.string() +
                                  " --set Continuum/Model=auto --set 'Scene/Gravity=0, -0.001'" +
                                  " --set 'Continuum/Mesh/Refinements=0'" +
                                  (force ? "" : " --set 'Particle/Conservative force/Type=none'"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find(force ? "Model = auto: compressible (stratification g H / c^2 0.02 "
                                    "<= 0.1, the thermal walls' epsilon 0.5 > 0.2 with a "
                                    "conservative force"
                                  : "Model = auto: low-Mach (stratification"),
              std::string::npos)
        << r.output;
  }
}
