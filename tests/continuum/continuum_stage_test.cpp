// `twinflow continuum CASE --out DIR` end to end: results, summary.json, refusal of bad input.
#include <gtest/gtest.h>

#include <algorithm>
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
  const Json summary = twinflow::io::read_json(out / "continuum" / "summary.json");
  const Json* results = twinflow::io::find(summary, {"results"});
  ASSERT_NE(results, nullptr);
  EXPECT_NEAR(twinflow::io::find(*results, {"nusselt_volume_average"})->get<double>(), 2.2448,
              1e-3 * 2.2448);
  EXPECT_NEAR(twinflow::io::find(summary, {"dimensionless", "rayleigh"})->get<double>(), 1e4, 1e-6);
  EXPECT_EQ((*twinflow::io::find(*results, {"mesh_study"})).size(), 2u);
  for (const char* phase : {"setup", "assembly", "solve", "total"})
    EXPECT_TRUE(twinflow::io::find(summary, {"wall_time_s", phase})->is_number()) << phase;
  EXPECT_NE(twinflow::io::find(summary, {"provenance"}), nullptr);

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

TEST(ContinuumStage, TransientModeEndToEnd) {
  // Mode = transient on the shipped case, shrunk to 8x8 and 5 steps: the time series (CSV and
  // summary.json) and the field snapshots as an XDMF temporal collection.
  const fs::path out = fresh_dir("transient");
  const Result r =
      run_twinflow("continuum " + kCase + " --out " + out.string() +
                   " --set 'Continuum/Mode=transient' --set 'Continuum/Mesh/Refinements=0'"
                   " --set 'Continuum/Time/End time=50' --set 'Continuum/Time/Time step=10'"
                   " --set 'Continuum/Time/Snapshot times=20'");
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path dir = out / "continuum";
  for (const char* f : {"summary.json", "time_series.csv", "fields.xdmf", "fields_mesh.h5",
                        "fields_0000.h5", "fields_0001.h5"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  EXPECT_FALSE(fs::exists(dir / "fields_0002.h5")); // snapshots at t = 20 and the end only
  const std::string xdmf = twinflow::io::read_file(dir / "fields.xdmf");
  EXPECT_NE(xdmf.find("CollectionType=\"Temporal\""), std::string::npos) << xdmf;
  EXPECT_NE(xdmf.find("Time Value=\"50\""), std::string::npos) << xdmf;
  const Json summary = twinflow::io::read_json(dir / "summary.json");
  EXPECT_EQ(twinflow::io::find(summary, {"continuum_parameters", "mode"})->get<std::string>(),
            "transient");
  const Json* results = twinflow::io::find(summary, {"results"});
  ASSERT_NE(results, nullptr);
  EXPECT_EQ(twinflow::io::find(*results, {"time_steps"})->get<double>(), 5);
  EXPECT_EQ(twinflow::io::find(*results, {"time"})->get<double>(), 50);
  const Json* series = twinflow::io::find(*results, {"time_series"});
  ASSERT_NE(series, nullptr);
  EXPECT_EQ((*twinflow::io::find(*series, {"time"})).size(), 6u); // t = 0 and five steps
  EXPECT_NEAR((*twinflow::io::find(*series, {"nusselt"})).front().get<double>(), 1.0,
              1e-10); // conduction
  EXPECT_GT((*twinflow::io::find(*series, {"kinetic_energy"})).back().get<double>(), 0.0);
  // CSV: a comment line, the header, one row per step.
  const std::string csv = twinflow::io::read_file(dir / "time_series.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 8) << csv;
}

TEST(ContinuumStage, ModeIsParsedAndCheckedAgainstTheCase) {
  const fs::path out = fresh_dir("mode");
  // The key is parsed and shown resolved, with an initial temperature (transient only).
  const Result printed = run_twinflow("check-case " + kCase +
                                      " --set 'Continuum/Mode=transient'"
                                      " --set 'Continuum/Time/End time=1'"
                                      " --set 'Continuum/Initial temperature=0.5 + x / Lx'");
  EXPECT_EQ(printed.code, 0) << printed.output;
  const auto begin = printed.output.find("set Mode ");
  ASSERT_NE(begin, std::string::npos) << printed.output;
  const std::string line = printed.output.substr(begin, printed.output.find('\n', begin) - begin);
  EXPECT_NE(line.find("= transient"), std::string::npos) << line;
  for (const char* set : {"Continuum/Mode=unsteady", "Continuum/Mode=transient", // no end time
                          "Continuum/Time/End time=5",                           // but steady
                          "Continuum/Time/Snapshot times=1", "Continuum/Time/Series every=0",
                          "Continuum/Initial temperature=1 + x"}) { // steady: no initial state
    const Result r = run_twinflow("continuum " + kCase + " --out " + out.string() + " --set '" +
                                  std::string(set) + "'");
    EXPECT_EQ(r.code, 2) << set << ": " << r.output;
    EXPECT_NE(r.output.find("Continuum/"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << set;
  }
}
