// `run` under mpirun, through a sweep whose every point runs under `--launcher 'mpirun -np 2
// {cmd}'`: each point's particle runs (its particle stage, its transport stage's runs) are split
// over two ranks, rank 0 alone runs the twins and the comparison. Three points finish, one fails
// under the launcher (its box is too short for two ranks) and is recorded as failed; point 000's
// files are the one-process run's, byte for byte, but for wall-clock times (which differ between
// any two runs). About 1-3 minutes on a busy 2-core machine: label validation. And a grid point
// under mpirun stopped by Ctrl-C / SIGTERM: interrupted with a checkpoint, continued.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "io/files.hpp"
#include "io/json.hpp"
#include "run_twinflow.hpp"

namespace fs = std::filesystem;
using twinflow::io::Json;

namespace {

std::string file_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Wall-clock times, by their keys: they differ between any two runs; and how a run was spread
// ("execution": ranks, threads), which is what differs on purpose.
bool is_timing(const std::string& key) {
  return key.find("seconds") != std::string::npos || key.find("wall_time") != std::string::npos ||
         key.find("steps_per_second") != std::string::npos || key == "execution";
}

Json without_timings(const Json& j) {
  if (j.is_object()) {
    Json out = Json::object();
    for (const auto& [key, value] : j.items())
      if (!is_timing(key)) out[key] = without_timings(value);
    return out;
  }
  if (j.is_array()) {
    Json out = Json::array();
    for (const auto& value : j) out.push_back(without_timings(value));
    return out;
  }
  return j;
}

// A CSV without its wall_seconds column (compare/error_vs_time.csv).
std::string without_wall_seconds(const std::string& csv) {
  std::istringstream in(csv);
  std::string line, out;
  int column = -1;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream cells_in(line);
    for (std::string cell; std::getline(cells_in, cell, ',');) cells.push_back(cell);
    if (column < 0 && line.rfind('#', 0) != 0)
      for (std::size_t c = 0; c < cells.size(); ++c)
        if (cells[c] == "wall_seconds") column = static_cast<int>(c);
    for (std::size_t c = 0; c < cells.size(); ++c)
      if (static_cast<int>(c) != column || line.rfind('#', 0) == 0) out += cells[c] + ",";
    out += "\n";
  }
  return out;
}

// Every file of the stages' folders; the run's files as they must agree.
void expect_same_results(const fs::path& one, const fs::path& two) {
  std::size_t compared = 0;
  for (const char* stage :
       {"particle", "transport", "continuum", "continuum_calibrated", "compare"}) {
    ASSERT_TRUE(fs::is_directory(one / stage)) << one / stage;
    for (const auto& entry : fs::directory_iterator(one / stage)) {
      const fs::path name = entry.path().filename();
      const fs::path other = two / stage / name;
      ASSERT_TRUE(fs::exists(other)) << other;
      // HDF5 files carry the snapshots' wall times; fields.csv and bins.csv hold their data.
      if (name.extension() == ".h5") continue;
      const std::string a = file_text(entry.path()), b = file_text(other);
      if (name.extension() == ".json")
        EXPECT_EQ(twinflow::io::dump(without_timings(Json::parse(a))),
                  twinflow::io::dump(without_timings(Json::parse(b))))
            << stage << "/" << name.string();
      else if (name == "error_vs_time.csv")
        EXPECT_EQ(without_wall_seconds(a), without_wall_seconds(b)) << name;
      else
        EXPECT_TRUE(a == b) << stage << "/" << name.string() << " differs";
      ++compared;
    }
  }
  EXPECT_GT(compared, 20u);
}

const std::string kMpiAsRoot = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                               "OMPI_MCA_rmaps_base_oversubscribe=1";

// The rows of DIR/<command>.json, in point order.
std::vector<Json> table_rows(const fs::path& table) {
  std::vector<Json> out;
  const Json j = twinflow::io::read_json(table);
  for (const auto& p : *twinflow::io::find(j, {"points"}))
    out.push_back(*twinflow::io::find(p, {"row"}));
  return out;
}

} // namespace

TEST(RunMpi, SweepPointsRunOnTwoRanksAsOnOneProcess) {
  const std::string cavity =
      std::string(TWINFLOW_SOURCE_DIR) + "/cases/heated_cavity_2d.prm" +
      " --set 'Scene/Density=1' --set 'Scene/Field bins=5, 5'"
      " --set 'Particle/Equilibration steps=200' --set 'Particle/Steps=400'"
      " --set 'Continuum/Mesh/Cells=4' --set 'Continuum/Mesh/Refinements=1'"
      " --set 'Transport/Measure kappa and eta=false' --set 'Transport/Kappa from walls=false'"
      " --set 'Transport/Diffusion repeats=1' --set 'Transport/Temperature=0.8' --threads 1";
  const fs::path dir = twinflow::testing::fresh_dir("run_mpi", "sweep");
  const fs::path cache = twinflow::testing::fresh_dir("run_mpi", "cache");
  const std::string launcher = std::string(TWINFLOW_MPIEXEC) + " -np 2 --bind-to none {cmd}";
  // The box is no transport input and the state point is fixed (else each point's own mean
  // temperature): one measurement (on two ranks, into the cache) serves the three points.
  const auto r = twinflow::testing::run_twinflow(
      "sweep " + cavity + " --vary 'Scene/Box size=10 10,12 10,10 12,10 2' --out " + dir.string() +
          " --launcher '" + launcher + "'",
      cache.string(), kMpiAsRoot);
  ASSERT_EQ(r.code, 0) << r.output;
  const Json table = twinflow::io::read_json(dir / "sweep.json");
  EXPECT_EQ(twinflow::io::text(table, {"launcher"}), launcher);
  const Json& points = *twinflow::io::find(table, {"points"});
  ASSERT_EQ(points.size(), 4u);
  for (std::size_t i = 0; i < 3; ++i) {
    const Json& row = *twinflow::io::find(points[i], {"row"});
    EXPECT_EQ(twinflow::io::text(row, {"status"}), "done")
        << twinflow::io::text(row, {"reason"}) << "\n"
        << file_text(dir / "points" / ("00" + std::to_string(i)) / "log.txt");
    EXPECT_GT(twinflow::io::number(row, {"nusselt_nominal"}), 0);
    EXPECT_EQ(twinflow::io::text(points[i], {"command"})
                  .rfind("exec " + std::string(TWINFLOW_MPIEXEC), 0),
              0u);
  }
  const Json& failed = *twinflow::io::find(points[3], {"row"});
  EXPECT_EQ(twinflow::io::text(failed, {"status"}), "failed");
  EXPECT_EQ(twinflow::io::number(failed, {"exit_code"}), 2);
  EXPECT_NE(twinflow::io::text(failed, {"reason"}).find("MPI ranks"), std::string::npos)
      << twinflow::io::text(failed, {"reason"});
  // Rank 0 alone printed: one "run: total wall time" line in the point's log.
  const std::string log = file_text(dir / "points/000/log.txt");
  EXPECT_NE(log.find("(particle runs on 2 MPI ranks)"), std::string::npos) << log;
  EXPECT_EQ(log.find("run: total wall time"), log.rfind("run: total wall time")) << log;

  // Point 000 on one process, measuring its own transport: the same results.
  const fs::path alone = twinflow::testing::fresh_dir("run_mpi", "alone");
  const auto one = twinflow::testing::run_twinflow(
      "run " + cavity + " --set 'Scene/Box size=10, 10' --out " + alone.string());
  ASSERT_EQ(one.code, 0) << one.output;
  expect_same_results(alone, dir / "points/000");
}

// Ctrl-C / SIGTERM under a launcher: the grid forwards it to the launcher (mpirun), which passes
// it to the ranks; they checkpoint. mpirun itself then ends with 1, not the ranks' 5: the point
// is `interrupted` because it was stopped and left a checkpoint, and the same command continues
// it on two ranks (--restart) to the end. Label validation: ~40 s alone, ~2.5 min beside
// another test on a busy 2-core machine.
TEST(LauncherMpi, PointStoppedBySignalIsInterruptedAndContinues) {
#ifndef TWINFLOW_MPIEXEC
  GTEST_SKIP() << "no mpirun";
#else
  const fs::path dir = twinflow::testing::fresh_dir("run_mpi", "signal");
  const std::string args =
      "stability " + std::string(TWINFLOW_SOURCE_DIR) + "/cases/heated_cavity_2d.prm" +
      " --set 'Scene/Box size=8, 8' --set 'Particle/Equilibration steps=100'"
      " --set 'Particle/Steps=50000' --vary 'Particle/Seed=1' --threads 1 --out " +
      dir.string() + " --launcher '" + TWINFLOW_MPIEXEC + " -np 2 --bind-to none {cmd}'";
  // Stopped once the particle stage has begun (its folder exists), as a user's Ctrl-C would.
  const fs::path script = dir.string() + ".sh";
  std::ofstream(script) << kMpiAsRoot << " TWINFLOW_CACHE=off " << TWINFLOW_BINARY << " " << args
                        << " > " << dir.string() << ".log 2>&1 &\npid=$!\n"
                        << "for i in $(seq 600); do [ -d " << (dir / "points/000/particle")
                        << " ] && break; sleep 0.1; done\nsleep 1\nkill -TERM $pid\nwait $pid\n";
  const int code = WEXITSTATUS(std::system(("bash " + script.string()).c_str()));
  EXPECT_EQ(code, 5) << file_text(dir.string() + ".log");
  auto rows_now = table_rows(dir / "stability.json");
  ASSERT_EQ(rows_now.size(), 1u);
  EXPECT_EQ(twinflow::io::text(rows_now[0], {"status"}), "interrupted")
      << twinflow::io::text(rows_now[0], {"reason"});
  EXPECT_TRUE(fs::exists(dir / "points/000/particle/checkpoint.twfc"));

  const auto again = twinflow::testing::run_twinflow(args, "off", kMpiAsRoot);
  ASSERT_EQ(again.code, 0) << again.output;
  rows_now = table_rows(dir / "stability.json");
  EXPECT_EQ(twinflow::io::text(rows_now[0], {"status"}), "stable")
      << twinflow::io::text(rows_now[0], {"reason"});
  EXPECT_NE(file_text(dir / "points/000/log.txt").find("resumed from step"), std::string::npos);
#endif
}
