// Ensembles' merge (study/ensemble.hpp) on small hand-made inputs whose answers are worked out
// by hand, and `--ensemble 2` end to end on the quick start: each realisation is the run of its
// seed, byte for byte; the merged files are their mean; a --restart keeps what was done.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>

#include "io/csv.hpp"
#include "io/files.hpp"
#include "io/json.hpp"
#include "run_twinflow.hpp"
#include "study/ensemble.hpp"

namespace fs = std::filesystem;
using twinflow::io::Json;
using namespace twinflow::study;

TEST(Ensemble, MeanTakesTheLargerOfSpreadAndBlocks) {
  // Values 1..4: sd = sqrt(5/3), sd / sqrt(4) = 0.6455; errors 0.1: sqrt(4 x 0.01) / 4 = 0.05.
  auto e = ensemble_mean({1, 2, 3, 4}, {0.1, 0.1, 0.1, 0.1});
  EXPECT_DOUBLE_EQ(e.mean, 2.5);
  EXPECT_NEAR(e.stderr_, std::sqrt(5.0 / 3.0) / 2, 1e-12);
  // Errors 2: sqrt(4 x 4) / 4 = 1 > 0.6455.
  e = ensemble_mean({1, 2, 3, 4}, {2, 2, 2, 2});
  EXPECT_NEAR(e.stderr_, 1.0, 1e-12);
}

TEST(Ensemble, ResultsMergeByTheirNames) {
  const Json a = Json::parse(R"({"N": 100, "T": 1.0, "T_stderr": 0.3, "wall_seconds": 3,
    "energy_relative_drift_max": 1e-5, "hint": "a", "pressure": 2.0,
    "walls": {"x_lower": {"q": 1.0, "q_stderr": 0.1, "q_stderr_blocking": [0.3, 0.4]}}})");
  const Json b = Json::parse(R"({"N": 100, "T": 2.0, "T_stderr": 0.4, "wall_seconds": 5,
    "energy_relative_drift_max": 3e-5, "hint": "b", "pressure": 3.0,
    "walls": {"x_lower": {"q": 3.0, "q_stderr": 0.1, "q_stderr_blocking": [0.4, 0.3]}}})");
  const Json m = merge_results({a, b});
  EXPECT_EQ(m["N"], 100);
  EXPECT_DOUBLE_EQ(m["T"].get<double>(), 1.5);
  // spread: sd = 0.7071, / sqrt 2 = 0.5; blocks: sqrt(0.09 + 0.16) / 2 = 0.25
  EXPECT_NEAR(m["T_stderr"].get<double>(), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(m["wall_seconds"].get<double>(), 8);
  EXPECT_DOUBLE_EQ(m["energy_relative_drift_max"].get<double>(), 3e-5);
  EXPECT_EQ(m["hint"], "a");
  EXPECT_DOUBLE_EQ(m["pressure"].get<double>(), 2.5);
  const Json& wall = m["walls"]["x_lower"];
  EXPECT_DOUBLE_EQ(wall["q"].get<double>(), 2);
  EXPECT_NEAR(wall["q_stderr"].get<double>(), 1.0, 1e-12); // the spread: |3 - 1| / 2
  EXPECT_NEAR(wall["q_stderr_blocking"][0].get<double>(), 0.25, 1e-12);
  // Keys keep their order.
  std::vector<std::string> keys;
  for (auto it = m.begin(); it != m.end(); ++it) keys.push_back(it.key());
  EXPECT_EQ(keys[1], "T");
  EXPECT_EQ(keys[2], "T_stderr");
}

TEST(Ensemble, TablesMergeColumnsWithErrorsAndKeepEqualOnes) {
  const std::string a = "# units\nx,y,T,T_se,n\n0.5,0.5,1,0.1,3\n1.5,0.5,2,0.1,4\n";
  const std::string b = "# units\nx,y,T,T_se,n\n0.5,0.5,1.5,0.3,3\n1.5,0.5,2,0.1,5\n";
  const auto t = twinflow::io::parse_csv(merge_table({a, b}, "fields.csv"));
  EXPECT_EQ(t.comments, "# units\n");
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0][0], "0.5");
  EXPECT_DOUBLE_EQ(std::stod(t.rows[0][2]), 1.25);
  // spread 0.25 against blocks sqrt(0.01 + 0.09) / 2 = 0.158
  EXPECT_NEAR(std::stod(t.rows[0][3]), 0.25, 1e-12);
  EXPECT_EQ(t.rows[0][4], "3");
  EXPECT_DOUBLE_EQ(std::stod(t.rows[1][4]), 4.5);
  EXPECT_NEAR(std::stod(t.rows[1][3]), std::sqrt(0.02) / 2, 1e-12); // equal values: the blocks'
  EXPECT_THROW(merge_table({a, "x,y\n1,2\n"}, "fields.csv"), std::runtime_error);
}

TEST(Ensemble, BlocksFollowOneAnother) {
  const std::string a = "block,bin,T_kinetic\n0,0,1\n0,1,2\n1,0,3\n1,1,4\n";
  const auto t = twinflow::io::parse_csv(concatenate_blocks({a, a}, "blocks.csv"));
  ASSERT_EQ(t.rows.size(), 8u);
  EXPECT_EQ(t.rows[4][0], "2");
  EXPECT_EQ(t.rows[7][0], "3");
  EXPECT_EQ(t.rows[7][2], "4");
}

TEST(Ensemble, SnapshotsMergeAndTheirCostsAdd) {
  twinflow::io::FieldFile::Contents a, b;
  a.grid.dim = 1;
  a.grid.counts = {{2, 1, 1}};
  b.grid = a.grid;
  twinflow::io::Snapshot s{10, 2.0, 1000, {{"density", 1, {1, 2}, {0.1, 0.1}}}};
  a.snapshots.push_back(s);
  s.fields[0].values = {3, 2};
  s.wall_seconds = 3;
  b.snapshots.push_back(s);
  const auto m = merge_snapshots({a, b});
  ASSERT_EQ(m.size(), 1u);
  EXPECT_DOUBLE_EQ(m[0].time, 10);
  EXPECT_DOUBLE_EQ(m[0].wall_seconds, 5);
  EXPECT_EQ(m[0].particle_steps, 2000);
  EXPECT_DOUBLE_EQ(m[0].fields[0].values[0], 2);
  EXPECT_NEAR(m[0].fields[0].standard_error[0], 1.0, 1e-12);
  EXPECT_NEAR(m[0].fields[0].standard_error[1], std::sqrt(0.02) / 2, 1e-12);
  b.snapshots.clear();
  EXPECT_THROW(merge_snapshots({a, b}), std::runtime_error);
}

namespace {
std::string file(const fs::path& p) {
  return twinflow::io::read_file(p);
}
} // namespace

// The quick start's particle stage, shortened, as an ensemble of 2 against its second seed
// alone; then the merged stage rebuilt by --restart from the realisations kept.
TEST(Ensemble, QuickStartRealisationsAreTheirSeedsRuns) {
  using twinflow::testing::run_twinflow;
  const fs::path dir = twinflow::testing::fresh_dir("ensemble_test", "quick");
  const fs::path alone = twinflow::testing::fresh_dir("ensemble_test", "seed4");
  const std::string case_file = std::string(TWINFLOW_SOURCE_DIR) + "/cases/quickstart_2d.prm";
  const std::string shorter = " --set Particle/Steps=2000 --threads 2";
  auto r = run_twinflow("particle " + case_file + " --seed 3 --ensemble 2 --out " + dir.string() +
                        shorter);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("realisation 2 of 2 (seed 4)"), std::string::npos) << r.output;
  r = run_twinflow("particle " + case_file + " --seed 4 --out " + alone.string() + shorter);
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path p = dir / "particle";
  EXPECT_EQ(file(p / "realisations" / "01" / "fields.csv"),
            file(alone / "particle" / "fields.csv"));
  const Json summary = twinflow::io::read_json(p / "summary.json");
  EXPECT_EQ(summary["results"]["ensemble"]["realisations"], 2);
  EXPECT_EQ(summary["parameters"]["Particle/Seed"], "3");
  // The merged temperature of bin 0: the realisations' mean.
  const auto merged = twinflow::io::parse_csv(file(p / "fields.csv"));
  const auto one = twinflow::io::parse_csv(file(p / "realisations" / "00" / "fields.csv"));
  const auto two = twinflow::io::parse_csv(file(p / "realisations" / "01" / "fields.csv"));
  const std::size_t t = merged.column("T_kinetic", "fields.csv");
  EXPECT_NEAR(std::stod(merged.rows[0][t]),
              0.5 * (std::stod(one.rows[0][t]) + std::stod(two.rows[0][t])), 1e-12);
  EXPECT_TRUE(fs::exists(p / "fields.h5"));
  // A stop after the first realisation: --restart keeps it and gives the same merged files.
  const std::string fields = file(p / "fields.csv");
  fs::remove(p / "summary.json");
  fs::remove(p / "realisations" / "01" / "summary.json");
  r = run_twinflow("particle " + case_file + " --seed 3 --ensemble 2 --restart --out " +
                   dir.string() + shorter);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("realisation 1 of 2 (seed 3): done earlier, kept"), std::string::npos)
      << r.output;
  EXPECT_EQ(file(p / "fields.csv"), fields);
}

// Stopped by --wall-time (which counts from the ensemble's start) wherever it happens to be, and
// continued with --restart until done: the same bytes as the run that was never stopped.
TEST(Ensemble, StoppedAndContinuedGivesTheSameBytes) {
  using twinflow::testing::run_twinflow;
  const fs::path whole = twinflow::testing::fresh_dir("ensemble_test", "whole");
  const fs::path stopped = twinflow::testing::fresh_dir("ensemble_test", "stopped");
  const std::string args = "particle " + std::string(TWINFLOW_SOURCE_DIR) +
                           "/cases/quickstart_2d.prm --ensemble 2 --threads 2 --set "
                           "Particle/Steps=6000 --out ";
  ASSERT_EQ(run_twinflow(args + whole.string()).code, 0);
  auto r = run_twinflow(args + stopped.string() + " --wall-time 1s");
  // Each stop resumes from its checkpoint, so the loop ends; the limit only guards against a
  // run that makes no progress. Alone 4-5 stops, beside another 2-thread job ~15.
  int stops = 0;
  while (r.code == 5 && stops < 60) {
    ++stops;
    r = run_twinflow(args + stopped.string() + " --wall-time 1s --restart");
  }
  ASSERT_EQ(r.code, 0) << r.output;
  std::cout << "stopped " << stops << " times\n";
  for (const char* name : {"fields.csv", "blocks.csv", "thermo.csv", "wall_layers.csv"})
    EXPECT_EQ(file(whole / "particle" / name), file(stopped / "particle" / name)) << name;
}
