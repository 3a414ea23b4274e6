// `twinflow continuum` with the low-Mach case file, end to end: dispatch on Model = low-mach,
// printed Ra, Pr, epsilon, summary.json with P/p0, fields (including the density n).
#include <gtest/gtest.h>

#include <filesystem>
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
  const Result r = run_twinflow("continuum " + case_file + " --out " + out.string() +
                                " --set 'Continuum/Mesh/Refinements=1'");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("low-Mach, steady, 2D, Ra = 100000, Pr = 0.71, epsilon = 0.6"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("P/p0 = "), std::string::npos) << r.output;
  for (const char* f : {"summary.json", "fields.h5", "fields.xdmf", "bins.csv", "wall_nusselt.csv"})
    EXPECT_TRUE(fs::exists(out / "continuum" / f)) << f;
  const Json summary = Json::parse(twinflow::io::read_file(out / "continuum" / "summary.json"));
  const Json* results = summary.find("results");
  ASSERT_NE(results, nullptr);
  EXPECT_EQ(summary.find("continuum_parameters")->find("model")->string(), "low-mach");
  EXPECT_NEAR(summary.find("dimensionless")->find("rayleigh")->number(), 1e5, 1e-6);
  EXPECT_NEAR(summary.find("dimensionless")->find("epsilon")->number(), 0.6, 1e-12);
  // 16x16 values of this solver (regression; 64x64: Nu = 4.5516, P/p0 = 0.8518, case header).
  EXPECT_NEAR(results->find("nusselt_volume_average")->number(), 4.53877, 1e-4);
  EXPECT_NEAR(results->find("pressure_ratio_P_over_p0")->number(), 0.853259, 1e-5);
  EXPECT_LT(std::abs(results->find("relative_mass_error")->number()), 1e-12);
}
