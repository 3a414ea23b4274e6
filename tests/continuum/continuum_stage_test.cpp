// `twinflow continuum CASE --out DIR` end to end: results, summary.json, refusal of bad input.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/wait.h>

#include "../run_twinflow.hpp"
#include "io/files.hpp"
#include "io/json.hpp"

namespace fs = std::filesystem;
using twinflow::io::Json;

namespace {

using twinflow::testing::Result;
using twinflow::testing::run_twinflow;

fs::path fresh_dir(const std::string& name) {
  return twinflow::testing::fresh_dir("continuum_stage_test", name);
}

const std::string kCase =
    std::string(TWINFLOW_SOURCE_DIR) + "/cases/continuum_de_vahl_davis_1e4.prm";

} // namespace

TEST(ContinuumStage, DeVahlDavisCaseEndToEnd) {
  // The shipped case shrunk to 16x16 (one refinement of 8x8): Nu = 2.24459 there (mesh study of
  // the cavity test), 1e-3 from the benchmark.
  const fs::path out = fresh_dir("dvd");
  const Result r = run_twinflow("continuum " + kCase + " --out " + out.string() +
                                " --set 'Continuum/Mesh/Refinements=1'");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find((out / "continuum").string()), std::string::npos) << r.output;
  for (const char* f : {"summary.json", "fields.h5", "fields.xdmf", "bins.csv", "wall_nusselt.csv"})
    EXPECT_TRUE(fs::exists(out / "continuum" / f)) << f;
  const Json summary = Json::parse(twinflow::io::read_file(out / "continuum" / "summary.json"));
  const Json* results = summary.find("results");
  ASSERT_NE(results, nullptr);
  EXPECT_NEAR(results->find("nusselt_volume_average")->number(), 2.2448, 1e-3 * 2.2448);
  EXPECT_NEAR(summary.find("dimensionless")->find("rayleigh")->number(), 1e4, 1e-6);
  EXPECT_EQ(results->find("mesh_study")->elements().size(), 2u);
  for (const char* phase : {"setup", "assembly", "solve", "total"})
    EXPECT_TRUE(summary.find("wall_time_s")->find(phase)->is_number()) << phase;
  EXPECT_NE(summary.find("provenance"), nullptr);

  // A finished stage is not overwritten without --force.
  const Result again = run_twinflow("continuum " + kCase + " --out " + out.string());
  EXPECT_EQ(again.code, 2) << again.output;
}

TEST(ContinuumStage, BadInputWritesNothing) {
  const fs::path out = fresh_dir("bad");
  for (const char* set :
       {"Continuum/Coefficients/Viscosity=0", "Continuum/Output/Probe points=40, 1",
        "Scene/Heat slabs/Power=1", "Continuum/Mesh/Cells=4, 4, 4"}) {
    const Result r = run_twinflow("continuum " + kCase + " --out " + out.string() + " --set '" +
                                  std::string(set) + "'");
    EXPECT_EQ(r.code, 2) << set << ": " << r.output;
    EXPECT_TRUE(r.output.find("Continuum/") != std::string::npos ||
                r.output.find("Scene/") != std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(out)) << set;
  }
}
