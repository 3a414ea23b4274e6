// twinflow sweep and stability through the command line: every point a child process, failed
// points recorded while the others finish, re-running skips finished points, a changed grid is
// refused, bad --vary input writes nothing, and the stability classes beside theory's limits.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/files.hpp"
#include "io/json.hpp"
#include "particle/theory.hpp"
#include "run_twinflow.hpp"

namespace fs = std::filesystem;
using twinflow::io::Json;
using twinflow::testing::Result;

namespace {

Result run(const std::string& args) {
  return twinflow::testing::run_twinflow(args);
}

fs::path fresh_dir(const std::string& name) {
  return twinflow::testing::fresh_dir("sweep_test", name);
}

std::string shipped(const std::string& name) {
  return std::string(TWINFLOW_SOURCE_DIR) + "/cases/" + name + ".prm";
}

// The rows of DIR/<command>.json, in point order.
std::vector<Json> rows(const fs::path& table) {
  std::vector<Json> out;
  const Json j = twinflow::io::read_json(table);
  for (const auto& p : (*twinflow::io::find(j, {"points"})))
    out.push_back(*twinflow::io::find(p, {"row"}));
  return out;
}

std::string text(const Json& row, const std::string& key) {
  return twinflow::io::text(row, {key});
}

double number(const Json& row, const std::string& key) {
  return twinflow::io::number(row, {key});
}

// OpenMPI refuses to run as root (CI does) without these; oversubscribing lets 2 ranks share a
// busy core.
const std::string kMpiAsRoot = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                               "OMPI_MCA_rmaps_base_oversubscribe=1";

std::string file_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The default cavity shrunk to 100 particles, 600 steps and a 4 x 4 (Q2) continuum mesh: one
// paired run takes ~15 s, nearly all of it the transport stage's fixed bulk runs.
const std::string kTinyScene = shipped("heated_cavity_2d") +
                               " --set 'Scene/Box size=10, 10' --set 'Scene/Density=1'"
                               " --set 'Scene/Field bins=5, 5'"
                               " --set 'Particle/Equilibration steps=200'"
                               " --set 'Particle/Steps=400' --set 'Continuum/Mesh/Cells=4'"
                               " --set 'Continuum/Mesh/Refinements=1'";
const std::string kTinyCavity = kTinyScene + " --set 'Transport/Measure kappa and eta=false'"
                                             " --set 'Transport/Kappa from walls=false'";
// The same with the case's measured coefficients, shrunk: kappa and eta by relaxation (2 runs of
// 100 particles; the heat slabs at the scene's scale would be the run's longest part).
const std::string kTinyMeasuredCavity = kTinyScene + " --set 'Transport/Flow particles=100'"
                                                     " --set 'Transport/Flow repeats=2'"
                                                     " --set 'Transport/Kappa from slabs=false'";

} // namespace

// Four points: one runs to the end, one fails at run time (dt = 2: a particle leaves the box in
// the first step, exit 4), two are rejected by the case (a Poiseuille force with walls along x).
TEST(Sweep, FailedPointsAreRecordedOthersFinishRerunSkipsChangedGridRefused) {
  const fs::path dir = fresh_dir("grid");
  const std::string grid = " --vary 'Particle/Time step=0.01,2' "
                           "--vary 'Scene/Reverse Poiseuille force=0,0.1' --jobs 2";
  const Result first = run("sweep " + kTinyCavity + " --out " + dir.string() + grid);
  ASSERT_EQ(first.code, 0) << first.output;
  EXPECT_NE(first.output.find("sweep: point 4/4 done"), std::string::npos) << first.output;

  const auto r = rows(dir / "sweep.json");
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(text(r[0], "status"), "done") << file_text(dir / "points/000/log.txt");
  EXPECT_EQ(number(r[0], "exit_code"), 0);
  EXPECT_EQ(text(r[0], "Particle/Time step"), "0.01");
  EXPECT_EQ(text(r[0], "Scene/Reverse Poiseuille force"), "0");
  EXPECT_GT(number(r[0], "rayleigh"), 0);
  // Conduction and a weak roll; the twin's walls from the wall model's theory pass less heat
  // than fixed wall temperatures would in this dilute (n = 1) box: their layers are ~1 rc.
  EXPECT_GT(number(r[0], "nusselt_nominal"), 0.5);
  EXPECT_GT(number(r[0], "wall_seconds"), 0);
  for (const std::size_t rejected : {1u, 3u}) {
    EXPECT_EQ(text(r[rejected], "status"), "failed");
    EXPECT_EQ(number(r[rejected], "exit_code"), 2);
    EXPECT_NE(text(r[rejected], "reason").find("Scene/Reverse Poiseuille force"),
              std::string::npos);
  }
  EXPECT_EQ(text(r[2], "status"), "failed");
  EXPECT_EQ(number(r[2], "exit_code"), 4);
  EXPECT_NE(text(r[2], "reason").find("unstable"), std::string::npos) << text(r[2], "reason");

  const std::string csv = file_text(dir / "sweep.csv");
  EXPECT_EQ(
      csv.rfind("point,status,reason,exit_code,Particle/Time step,Scene/Reverse Poiseuille force,"
                "target_rayleigh,gravity,wall_seconds,",
                0),
      0u)
      << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5) << csv;

  // The same command again: the finished point is not run again.
  const auto log_time = fs::last_write_time(dir / "points/000/log.txt");
  const Result again = run("sweep " + kTinyCavity + " --out " + dir.string() + grid);
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_NE(again.output.find("point 000 skipped"), std::string::npos) << again.output;
  EXPECT_EQ(fs::last_write_time(dir / "points/000/log.txt"), log_time);
  EXPECT_EQ(text(rows(dir / "sweep.json")[0], "status"), "done");

  // Another grid in the same directory: refused, nothing changed.
  const std::string table = file_text(dir / "sweep.csv");
  const Result changed = run("sweep " + kTinyCavity + " --out " + dir.string() +
                             " --vary 'Particle/Time step=0.01,3' --jobs 2");
  EXPECT_EQ(changed.code, 2) << changed.output;
  EXPECT_NE(changed.output.find("another grid"), std::string::npos) << changed.output;
  EXPECT_EQ(file_text(dir / "sweep.csv"), table);
}

TEST(Sweep, BadVaryOrRayleighExitsTwoAndWritesNothing) {
  const fs::path out = fresh_dir("bad");
  const std::string cavity = shipped("heated_cavity_2d");
  struct Case {
    std::string args, expect;
  } cases[] = {
      {"sweep " + cavity + " --vary 'Particle/No such key=1,2'", "Particle/No such key"},
      {"sweep " + cavity + " --vary 'Particle/Time step=0.01,fast'", "Particle/Time step"},
      {"sweep " + cavity + " --vary 'Particle/Time step'", "Section/Key=V1,V2"},
      {"sweep " + cavity + " --vary 'Particle/Time step=0.01,,0.02'", "empty value"},
      {"sweep " + cavity + " --vary 'Particle/Time step=0.01' --vary 'Particle/Time step=0.02'",
       "varied twice"},
      {"sweep " + cavity, "needs at least one --vary"},
      {"stability " + cavity + " --vary 'Scene/Reverse Poiseuille force=0.1'",
       "no point of the grid is a valid case"},
      {"sweep " + cavity + " --vary 'Particle/Time step=0.01' --jobs 0", "--jobs"},
      {"run " + cavity + " --vary 'Particle/Time step=0.01'", "--vary belongs to sweep"},
      {"sweep " + cavity + " --rayleigh 1e3,x", "--rayleigh"},
      {"sweep " + shipped("equilibrium_ideal_3d") + " --rayleigh 1e3", "Scene/Gravity"},
      {"sweep " + cavity + " --rayleigh 1e3 --set 'Scene/x boundaries/Upper wall temperature=1.5'",
       "heated direction"},
      {"stability " + cavity + " --vary 'Particle/Seed=1' --launcher 'mpirun -np 2'", "no {cmd}"},
      {"sweep " + cavity + " --vary 'Particle/Seed=1' --launcher '{cmd} {cmd}'", "{cmd} 2 times"},
      {"sweep " + cavity + " --vary 'Particle/Seed=1' --launcher 'no-such-launcher -n 2 {cmd}'",
       "'no-such-launcher' not found"},
      {"sweep " + cavity + " --vary 'Particle/Seed=1' --launcher \"mpirun -np 2 '{cmd}\"",
       "not valid shell syntax"},
      {"run " + cavity + " --launcher 'mpirun -np 2 {cmd}'", "--launcher belongs to sweep"},
  };
  for (const auto& c : cases) {
    const Result r = run(c.args + " --out " + out.string());
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

// Between thermal walls the fluid's mean temperature is not the walls' mean (the default cavity
// starts at 0.8 and settles near 0.9 between 1.5 and 0.5): a stable run is held to the walls'
// range, where the walls' mean (the target before) would call it temperature_off.
TEST(Stability, WalledSceneIsHeldToTheWallsRange) {
  const fs::path dir = fresh_dir("stability_walls");
  const Result r = run("stability " + shipped("heated_cavity_2d") +
                       " --set 'Scene/Box size=8, 8' --set 'Scene/Field bins=4, 4'"
                       " --set 'Particle/Equilibration steps=500' --set 'Particle/Steps=1500'"
                       " --vary 'Particle/Time step=0.01' --jobs 1 --out " +
                       dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto rows_now = rows(dir / "stability.json");
  ASSERT_EQ(rows_now.size(), 1u);
  const Json& point = rows_now[0];
  EXPECT_EQ(text(point, "status"), "stable") << text(point, "reason");
  EXPECT_EQ(number(point, "temperature_relative_error"), 0);
  for (const char* T : {"T_kinetic", "T_internal"}) {
    EXPECT_GT(number(point, T), 0.5) << T;
    EXPECT_LT(number(point, T), 1.5) << T;
    EXPECT_GT(std::abs(number(point, T) / number(point, "T_target") - 1), 0.05) << T;
  }
}

// --rayleigh: each point's twin runs at its target Ra. Before issue 31 gravity came from a run at
// the walls' mean temperature while each twin took coefficients measured at its particle
// fluid's mean temperature (alpha = 1/T alone differed by the ratio of the two). With a cache of
// its own, as a user's sweep has one: one measurement serves both points (gravity is none of its
// inputs), and each point's run takes the coefficients its gravity was set with.
TEST(Sweep, RayleighPointsLandOnTheirTargets) {
  const fs::path dir = fresh_dir("rayleigh"), cache = fresh_dir("rayleigh_cache");
  const Result r = twinflow::testing::run_twinflow(
      "sweep " + kTinyMeasuredCavity + " --rayleigh 20,60 --jobs 2 --out " + dir.string(),
      cache.string());
  ASSERT_EQ(r.code, 0) << r.output;
  // The transport stage runs before the particles, at Scene/Temperature: said.
  EXPECT_NE(r.output.find("Transport/Temperature=0.8"), std::string::npos) << r.output;
  const auto points = rows(dir / "sweep.json");
  ASSERT_EQ(points.size(), 2u);
  for (const Json& p : points) {
    const std::string name = text(p, "point");
    ASSERT_EQ(text(p, "status"), "done")
        << text(p, "reason") << file_text(dir / "points" / name / "log.txt");
    EXPECT_NEAR(number(p, "rayleigh") / number(p, "target_rayleigh"), 1, 0.03) << name;
    EXPECT_EQ(number(p, "transport_temperature"), 0.8);
    EXPECT_GT(number(p, "particle_temperature"), 0); // the fluid's own, beside the pinned one
    const Json reference =
        twinflow::io::read_json(dir / "reference" / name / "transport" / "summary.json");
    const Json own = twinflow::io::read_json(dir / "points" / name / "transport" / "summary.json");
    EXPECT_NE(file_text(dir / "points" / name / "log.txt").find("reused from the cache"),
              std::string::npos)
        << name << ": its run measured again";
    for (const char* key : {"conductivity", "viscosity"})
      EXPECT_EQ(twinflow::io::number(reference, {"results", "measured", key}),
                twinflow::io::number(own, {"results", "measured", key}))
          << name << " " << key;
  }
  const std::string csv = file_text(dir / "sweep.csv");
  EXPECT_EQ(
      csv.rfind("point,status,reason,exit_code,target_rayleigh,rayleigh,gravity,wall_seconds,", 0),
      0u)
      << csv;
}

// A small periodic ideal DPDE box: dt = 0.005 is stable, dt = 2 is not; the table states
// 001:(28)'s dt_c and 000:(3.34)'s number exactly as particle/theory computes them.
TEST(Stability, ClassifiesPointsBesideTheoryLimits) {
  const fs::path dir = fresh_dir("stability");
  const std::string args =
      "stability " + shipped("equilibrium_ideal_3d") +
      " --set 'Scene/Box size=4, 4, 4' --set 'Particle/Equilibration steps=200'"
      " --set 'Particle/Steps=1000' --set 'Particle/Dissipation/Parametrisation=constant-gamma'"
      " --vary 'Particle/Time step=0.005,2' --jobs 2 --out " +
      dir.string();
  const Result r = run(args);
  ASSERT_EQ(r.code, 0) << r.output;
  const auto rows_now = rows(dir / "stability.json");
  ASSERT_EQ(rows_now.size(), 2u);
  const Json &small = rows_now[0], &huge = rows_now[1];
  EXPECT_EQ(text(small, "status"), "stable") << text(small, "reason");
  const std::string status = text(huge, "status");
  EXPECT_TRUE(status == "non_finite" || status == "negative_internal_energy" ||
              status == "unstable" || status == "energy_drift")
      << status << ": " << text(huge, "reason");
  EXPECT_LT(number(small, "energy_relative_drift_max"), 1e-10);
  EXPECT_LT(number(small, "temperature_relative_error"), 0.05);

  // The case's fluid, as particle/theory takes it.
  twinflow::particle::ParticleParameters p;
  p.dim = 3;
  p.density = 3;
  p.temperature = 1;
  p.friction = twinflow::particle::Friction::ConstantGamma;
  p.gamma = 4.5;
  p.dissipation = {1.0, 2.0};
  p.cv = 10;
  p.heat = twinflow::particle::HeatLaw::Inverse;
  p.heat_coefficient = twinflow::particle::HeatCoefficient::Constant;
  p.kappa0 = 10;
  p.heat_weight = {1.0, 2.0};
  const double dt_c = twinflow::particle::marsh_yeomans_critical_dt(p);
  for (const Json* row : {&small, &huge}) {
    p.dt = number(*row, "dt");
    EXPECT_DOUBLE_EQ(number(*row, "predicted_dt_critical"), dt_c);
    EXPECT_DOUBLE_EQ(number(*row, "fluctuation_number"),
                     twinflow::particle::fluctuation_stability_number(p));
  }
  EXPECT_NE(twinflow::io::find(small, {"predicted_stable"})->dump().find("true"),
            std::string::npos);
  EXPECT_NE(twinflow::io::find(huge, {"predicted_stable"})->dump().find("false"),
            std::string::npos);

  const std::string csv = file_text(dir / "stability.csv");
  EXPECT_EQ(csv.rfind("point,status,reason,exit_code,Particle/Time step,dt,predicted_dt_critical,"
                      "fluctuation_number,predicted_stable,energy_relative_drift_max,T_kinetic,"
                      "T_internal,T_target,temperature_relative_error,wall_seconds\n",
                      0),
            0u)
      << csv;

  // Again: both results stand (a blow-up is a result too), nothing runs.
  const Result again = run(args);
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_NE(again.output.find("2 points, 0 to run"), std::string::npos) << again.output;
}

// --launcher: every point runs under `mpirun -np 2` (its particle run split over two ranks), the
// launcher and each point's command are recorded, a blow-up is classified as without one, and a
// point's results are the one-process run's, byte for byte (the decomposition's promise).
TEST(Stability, LauncherRunsEachPointOnTwoRanks) {
#ifndef TWINFLOW_MPIEXEC
  GTEST_SKIP() << "no mpirun";
#else
  const fs::path dir = fresh_dir("stability_launcher");
  const std::string scene = shipped("heated_cavity_2d") +
                            " --set 'Scene/Box size=8, 8' --set 'Scene/Field bins=4, 4'"
                            " --set 'Particle/Equilibration steps=100' --set 'Particle/Steps=300'";
  const std::string launcher = std::string(TWINFLOW_MPIEXEC) + " -np 2 --bind-to none {cmd}";
  const Result r = twinflow::testing::run_twinflow(
      "stability " + scene +
          " --vary 'Particle/Time step=0.01,2' --vary 'Particle/Seed=1,2' --threads 1 --out " +
          dir.string() + " --launcher '" + launcher + "'",
      "off", kMpiAsRoot);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("4 to run, 1 at a time, 1 thread(s) each, each under '" + launcher),
            std::string::npos)
      << r.output;
  const auto rows_now = rows(dir / "stability.json");
  ASSERT_EQ(rows_now.size(), 4u);
  for (const std::size_t stable : {0u, 1u})
    EXPECT_EQ(text(rows_now[stable], "status"), "stable")
        << text(rows_now[stable], "reason") << file_text(dir / "points/000/log.txt");
  for (const std::size_t blown : {2u, 3u}) {
    EXPECT_EQ(number(rows_now[blown], "exit_code"), 4) << text(rows_now[blown], "reason");
    EXPECT_NE(text(rows_now[blown], "status"), "failed") << text(rows_now[blown], "reason");
    EXPECT_NE(text(rows_now[blown], "reason").find("unstable at step"), std::string::npos);
  }
  const Json table = twinflow::io::read_json(dir / "stability.json");
  EXPECT_EQ(text(table, "launcher"), launcher);
  const Json& first = (*twinflow::io::find(table, {"points"}))[0];
  const std::string command = text(first, "command");
  EXPECT_EQ(command.rfind("exec " + std::string(TWINFLOW_MPIEXEC) + " -np 2 --bind-to none /", 0),
            0u)
      << command;
  EXPECT_NE(command.find(" particle "), std::string::npos) << command;
  EXPECT_NE(file_text(dir / "points/000/log.txt").find(command), std::string::npos);

  // Point 000 again on one process, no launcher: the same bytes.
  const fs::path alone = fresh_dir("stability_launcher_alone");
  const Result one = run("particle " + scene + " --set 'Particle/Time step=0.01'" +
                         " --set 'Particle/Seed=1' --threads 1 --out " + alone.string());
  ASSERT_EQ(one.code, 0) << one.output;
  for (const char* f : {"thermo.csv", "fields.csv"})
    EXPECT_EQ(file_text(dir / "points/000/particle" / f), file_text(alone / "particle" / f)) << f;
#endif
}

// --plan (a job array's first step, docs/cluster.md): the table with every point pending and each
// point's command as DIR/points/NNN/command.sh, nothing run; a point's script run on its own (as
// an array task would) is then skipped by the same command without --plan, which runs the rest.
TEST(Stability, PlanWritesEachPointsCommandForAJobArray) {
  const fs::path dir = fresh_dir("stability_plan");
  const std::string args = "stability " + shipped("heated_cavity_2d") +
                           " --set 'Scene/Box size=8, 8' --set 'Particle/Equilibration steps=100'"
                           " --set 'Particle/Steps=300' --vary 'Particle/Seed=1,2' --threads 1"
                           " --out " +
                           dir.string();
  const Result plan = run(args + " --plan");
  ASSERT_EQ(plan.code, 0) << plan.output;
  EXPECT_NE(plan.output.find("planned 2 of 2 points, nothing run"), std::string::npos)
      << plan.output;
  for (const auto& row : rows(dir / "stability.json")) EXPECT_EQ(text(row, "status"), "pending");
  const std::string script = file_text(dir / "points/001/command.sh");
  EXPECT_NE(script.find(" particle "), std::string::npos) << script;
  EXPECT_NE(script.find("--set Particle/Seed=2"), std::string::npos) << script;
  EXPECT_FALSE(fs::exists(dir / "points/000/particle"));

  const int task =
      std::system(("sh " + (dir / "points/000/command.sh").string() + " > /dev/null 2>&1").c_str());
  ASSERT_EQ(task, 0);
  // Planned again: only the unfinished point keeps a script.
  const Result replan = run(args + " --plan");
  ASSERT_EQ(replan.code, 0) << replan.output;
  EXPECT_NE(replan.output.find("planned 1 of 2 points"), std::string::npos) << replan.output;
  EXPECT_FALSE(fs::exists(dir / "points/000/command.sh"));
  EXPECT_TRUE(fs::exists(dir / "points/001/command.sh"));
  const Result table = run(args);
  ASSERT_EQ(table.code, 0) << table.output;
  EXPECT_NE(table.output.find("point 000 skipped (finished earlier: stable)"), std::string::npos)
      << table.output;
  const auto rows_now = rows(dir / "stability.json");
  ASSERT_EQ(rows_now.size(), 2u);
  for (const auto& row : rows_now) EXPECT_EQ(text(row, "status"), "stable") << text(row, "reason");
}
