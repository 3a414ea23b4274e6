// The twinflow command line's runs: interrupted and killed runs restart to the same bytes, `run`
// reuses unchanged stages, a run says how it ran, the transport stage's threads and cache.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/files.hpp"
#include "io/json.hpp"
#include "run_twinflow.hpp"

namespace fs = std::filesystem;

namespace {

using twinflow::testing::Result;
using twinflow::testing::run_command;
Result run(const std::string& args) {
  return twinflow::testing::run_twinflow(args);
}

fs::path fresh_dir(const std::string& name) {
  return twinflow::testing::fresh_dir("cli_run_test", name);
}

} // namespace

// A run stopped by the wall-time limit or a signal writes a checkpoint and exits with 5;
// --restart continues it to byte-identical outputs; a changed case cannot continue it.
TEST(Cli, InterruptedRunRestartsToIdenticalOutputs) {
  const std::string c = std::string(TWINFLOW_SOURCE_DIR) + "/cases/heated_cavity_2d.prm";
  const std::string size =
      " --set 'Particle/Equilibration steps=500' --set 'Particle/Steps=2500' --threads 1";
  const fs::path whole = fresh_dir("whole"), parts = fresh_dir("parts");
  ASSERT_EQ(run("particle " + c + " --out " + whole.string() + size).code, 0);

  EXPECT_EQ(run("particle " + c + " --out " + parts.string() + size + " --restart").code, 2)
      << "nothing to restart";
  const Result stopped =
      run("particle " + c + " --out " + parts.string() + size + " --wall-time 0.5");
  ASSERT_EQ(stopped.code, 5) << stopped.output;
  EXPECT_NE(stopped.output.find("--restart"), std::string::npos);
  ASSERT_TRUE(fs::exists(parts / "particle" / "checkpoint.twfc"));
  const Result changed =
      run("particle " + c + " --out " + parts.string() + size + " --seed 99 --restart");
  EXPECT_EQ(changed.code, 2);
  EXPECT_NE(changed.output.find("other case parameters"), std::string::npos) << changed.output;
  // The hint is the exact command: every option of the stopped run, shell-quoted, --restart.
  const std::string tag = "continue with: ";
  const auto at = stopped.output.find(tag);
  ASSERT_NE(at, std::string::npos) << stopped.output;
  const std::string hint =
      stopped.output.substr(at + tag.size(), stopped.output.find('\n', at) - at - tag.size());
  EXPECT_NE(hint.find("'Particle/Equilibration steps=500'"), std::string::npos) << hint;
  EXPECT_NE(hint.find("--threads 1"), std::string::npos) << hint;
  EXPECT_NE(hint.find("--restart"), std::string::npos) << hint;
  // It keeps --wall-time 0.5: each run continues for half a second, until one finishes.
  Result resumed = run_command("TWINFLOW_CACHE=off " + hint);
  for (int again = 0; resumed.code == 5 && again < 40; ++again) {
    EXPECT_NE(resumed.output.find(hint), std::string::npos) << "the same hint each time";
    resumed = run_command("TWINFLOW_CACHE=off " + hint);
  }
  ASSERT_EQ(resumed.code, 0) << hint << "\n" << resumed.output;
  EXPECT_NE(resumed.output.find("resumed from step "), std::string::npos) << resumed.output;
  EXPECT_NE(resumed.output.find("(checkpoint of 20"), std::string::npos) << resumed.output;
  EXPECT_FALSE(fs::exists(parts / "particle" / "checkpoint.twfc"));
  for (const char* f :
       {"thermo.csv", "fields.csv", "histograms.csv", "rdf.csv", "wall_layers.csv"}) {
    std::ifstream a(whole / "particle" / f), b(parts / "particle" / f);
    std::stringstream sa, sb;
    sa << a.rdbuf(), sb << b.rdbuf();
    EXPECT_EQ(sa.str(), sb.str()) << f;
    EXPECT_FALSE(sa.str().empty()) << f;
  }

  // SIGTERM: the same clean stop (sent once the run has created its folder).
  const fs::path killed = fresh_dir("killed");
  const Result term = run("particle " + c + " --out " + killed.string() +
                          " --threads 1 2>&1 & pid=$!; until [ -d " + killed.string() +
                          "/particle ]; do sleep 0.1; done; sleep 0.3; kill -TERM $pid; wait $pid");
  EXPECT_EQ(term.code, 5) << term.output;
  EXPECT_NE(term.output.find("interrupted by a signal"), std::string::npos) << term.output;
  EXPECT_TRUE(fs::exists(killed / "particle" / "checkpoint.twfc"));
}

// kill -9 after the first periodic checkpoint (Particle/Checkpoint interval): --restart continues
// from it to outputs byte-identical to an uninterrupted run's.
TEST(Cli, KilledRunRestartsFromItsPeriodicCheckpointToIdenticalOutputs) {
  const std::string c = std::string(TWINFLOW_SOURCE_DIR) + "/cases/heated_cavity_2d.prm";
  const std::string size =
      " --set 'Particle/Equilibration steps=500' --set 'Particle/Steps=4000' --threads 1";
  const fs::path whole = fresh_dir("kill_whole"), killed = fresh_dir("kill_parts");
  ASSERT_EQ(run("particle " + c + " --out " + whole.string() + size).code, 0);
  const fs::path checkpoint = killed / "particle" / "checkpoint.twfc";
  const Result kill = run("particle " + c + " --out " + killed.string() + size +
                          " --set 'Particle/Checkpoint interval=0.005' 2>&1 & pid=$!; "
                          "until [ -f " +
                          checkpoint.string() +
                          " ] || ! kill -0 $pid 2>/dev/null; do sleep 0.02; done; "
                          "kill -KILL $pid; wait $pid");
  ASSERT_TRUE(fs::exists(checkpoint)) << kill.output;
  ASSERT_FALSE(fs::exists(killed / "particle" / "summary.json")) << "finished before the kill";
  // The interval changes no result: a restart with the default interval continues it.
  const Result resumed = run("particle " + c + " --out " + killed.string() + size + " --restart");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resumed from step "), std::string::npos) << resumed.output;
  EXPECT_FALSE(fs::exists(checkpoint));
  for (const char* f : {"thermo.csv", "fields.csv", "histograms.csv", "rdf.csv", "wall_layers.csv",
                        "blocks.csv", "correlations.csv"}) {
    std::ifstream a(whole / "particle" / f), b(killed / "particle" / f);
    std::stringstream sa, sb;
    sa << a.rdbuf(), sb << b.rdbuf();
    EXPECT_EQ(sa.str(), sb.str()) << f;
    EXPECT_FALSE(sa.str().empty()) << f;
  }
}

// `run` on a tiny cavity: every stage, then compare's metrics; the same command again reuses
// every stage by its inputs hash; a changed continuum key reruns only the continuum twins; a
// changed particle key needs --force; `compare` alone rewrites only compare/.
// The default cavity shrunk to seconds: 10 x 10 rc at density 1, 5 x 5 bins, a 4 x 4 mesh.
static std::string tiny_cavity(int equilibration, int steps, int refinements) {
  return std::string(TWINFLOW_SOURCE_DIR) + "/cases/heated_cavity_2d.prm --threads 1" +
         " --set 'Scene/Box size=10, 10' --set 'Scene/Density=1' --set 'Scene/Field bins=5, 5'" +
         " --set 'Particle/Equilibration steps=" + std::to_string(equilibration) + "'" +
         " --set 'Particle/Steps=" + std::to_string(steps) + "'" +
         " --set 'Continuum/Mesh/Cells=4' --set 'Continuum/Mesh/Refinements=" +
         std::to_string(refinements) + "' --set 'Transport/Measure kappa and eta=false'" +
         " --set 'Transport/Kappa from walls=false'";
}

TEST(Cli, RunComparesTheTwinsAndReusesUnchangedStages) {
  const std::string tiny = tiny_cavity(200, 400, 1);
  const fs::path dir = fresh_dir("reuse");
  const Result first = run("run " + tiny + " --out " + dir.string());
  ASSERT_EQ(first.code, 0) << first.output;
  const auto metrics = twinflow::io::read_json(dir / "compare" / "metrics.json");
  const auto* row = twinflow::io::find(metrics, {"table_row"});
  ASSERT_NE(row, nullptr);
  for (const char* key :
       {"nusselt_particle", "nusselt_particle_stderr", "nusselt_nominal", "nusselt_calibrated",
        "temperature_l2_nominal", "temperature_l2_calibrated", "temperature_l2_noise"}) {
    ASSERT_NE(twinflow::io::find(*row, {key}), nullptr) << key;
    EXPECT_TRUE(std::isfinite(twinflow::io::find(*row, {key})->get<double>())) << key;
  }
  // 5 x 5 bins of 2 rc, wall layer 1 rc: the 3 x 3 interior
  EXPECT_EQ(twinflow::io::find(metrics, {"interior_bins"})->get<double>(), 9);
  for (const char* f : {"bins.csv", "profiles.csv", "error_vs_time.csv"})
    EXPECT_TRUE(fs::exists(dir / "compare" / f)) << f;
  // The Kapitza twin's heat-flux error includes its conductances' errors (one solve per wall
  // with an h_K, moved by its error): more conductance, more heat, and the total covers each
  // part. (A wall whose measured jump has the wrong sign in this tiny run gets the fluid's wall
  // temperature instead, and no h_K: which walls have one depends on the realisation.)
  {
    const auto calibrated = twinflow::io::read_json(dir / "continuum_calibrated" / "summary.json");
    const auto* u = twinflow::io::find(calibrated, {"coefficient_uncertainty"});
    ASSERT_NE(u, nullptr) << first.output;
    const double total = twinflow::io::find(*u, {"heat_flux_relative_stderr"})->get<double>();
    const auto* parameters = twinflow::io::find(calibrated, {"continuum_parameters"});
    ASSERT_NE(parameters, nullptr);
    const auto* boundaries = twinflow::io::find(*parameters, {"boundaries"});
    ASSERT_TRUE(boundaries != nullptr && boundaries->is_array());
    const auto& x_walls = boundaries->at(0);
    int with_conductance = 0;
    for (const char* side : {"lower", "upper"}) {
      const auto* wall_side = twinflow::io::find(x_walls, {side});
      ASSERT_NE(wall_side, nullptr) << side;
      const auto* h = twinflow::io::find(*wall_side, {"kapitza_conductance_stderr"});
      if (h == nullptr || !(h->get<double>() > 0)) continue;
      ++with_conductance;
      const std::string wall = std::string("kapitza_x_") + side;
      const auto* k = twinflow::io::find(*u, {wall});
      ASSERT_NE(k, nullptr) << wall << "\n" << first.output;
      EXPECT_EQ(twinflow::io::find(*k, {"stderr"})->get<double>(), h->get<double>()) << wall;
      const double change = twinflow::io::find(*k, {"heat_flux_relative_change"})->get<double>();
      EXPECT_GT(change, 0) << wall;
      EXPECT_GE(total, change) << wall;
    }
    EXPECT_GE(with_conductance, 1) << first.output;
  }

  const Result again = run("run " + tiny + " --out " + dir.string());
  ASSERT_EQ(again.code, 0) << again.output;
  for (const char* stage : {"particle", "transport", "continuum", "continuum_calibrated"})
    EXPECT_NE(again.output.find(std::string("run: ") + stage + ": inputs unchanged"),
              std::string::npos)
        << stage << "\n"
        << again.output;

  // --restart after a finished particle stage (a stop in a later stage) goes on from it.
  const Result restarted = run("run " + tiny + " --out " + dir.string() + " --restart");
  ASSERT_EQ(restarted.code, 0) << restarted.output;
  EXPECT_NE(restarted.output.find("run: particle: inputs unchanged"), std::string::npos)
      << restarted.output;

  const Result mesh = run("run " + tiny + " --set 'Continuum/Mesh/Cells=2' --out " + dir.string());
  ASSERT_EQ(mesh.code, 0) << mesh.output;
  EXPECT_NE(mesh.output.find("run: particle: inputs unchanged"), std::string::npos);
  EXPECT_NE(mesh.output.find("run: transport: inputs unchanged"), std::string::npos);
  EXPECT_EQ(mesh.output.find("run: continuum: inputs unchanged"), std::string::npos);

  // A record made before a parameter existed lacks it: still the same inputs when the new
  // parameter has its default (here: drop one from particle/inputs.json and spoil its hash).
  {
    auto inputs = twinflow::io::read_json(dir / "particle" / "inputs.json");
    twinflow::io::Json older = twinflow::io::Json::object();
    for (const auto& [key, value] : twinflow::io::find(inputs, {"parameters"})->items())
      if (key != "Scene/Temperature perturbation") older[key] = value;
    inputs["parameters"] = older;
    inputs["hash"] = "0000000000000000";
    twinflow::io::write_file_atomically(dir / "particle" / "inputs.json",
                                        twinflow::io::dump(inputs));
    const Result old_record = run("run " + tiny + " --out " + dir.string());
    ASSERT_EQ(old_record.code, 0) << old_record.output;
    EXPECT_NE(old_record.output.find("run: particle: inputs unchanged"), std::string::npos)
        << old_record.output;
    const Result other =
        run("run " + tiny + " --set 'Scene/Temperature perturbation=0.1' --out " + dir.string());
    EXPECT_EQ(other.code, 2) << other.output; // not its default: a changed particle stage
    EXPECT_NE(other.output.find("--force"), std::string::npos) << other.output;
  }

  const Result changed = run("run " + tiny + " --seed 5 --out " + dir.string());
  EXPECT_EQ(changed.code, 2) << changed.output;
  EXPECT_NE(changed.output.find("--force"), std::string::npos) << changed.output;

  // compare RUNDIR takes the case the twins ran (RUNDIR/case.json): the run's metrics again.
  const auto without_timing = [](twinflow::io::Json m) {
    m.erase("execution");
    m.erase("stage_wall_time_s");
    return m;
  };
  const auto by_run = twinflow::io::read_json(dir / "compare" / "metrics.json");
  const Result compare = run("compare " + dir.string());
  EXPECT_EQ(compare.code, 0) << compare.output;
  EXPECT_EQ(without_timing(twinflow::io::read_json(dir / "compare" / "metrics.json")),
            without_timing(by_run));
  EXPECT_EQ(run("compare " + (dir / "no-such-run").string()).code, 2);
  EXPECT_EQ(run("compare " + dir.string() + " --set Particle/Seed=3").code, 2);
  // The twin's kappa here is theory's (no error): the particle Nu has the heat flow's error
  // only. With a measured kappa (planted: 2% error) it also states Nu with q0's kappa error.
  {
    const auto& particle = *twinflow::io::find(by_run, {"particle"});
    EXPECT_EQ(twinflow::io::find(particle, {"nusselt_stderr_with_conductivity"}), nullptr);
    const fs::path measured = fresh_dir("measured_kappa");
    fs::copy(dir, measured, fs::copy_options::recursive);
    auto twin = twinflow::io::read_json(measured / "continuum" / "summary.json");
    twin["coefficient_uncertainty"]["conductivity"] = {{"value", 20.0}, {"stderr", 0.4}};
    twinflow::io::write_file_atomically(measured / "continuum" / "summary.json",
                                        twinflow::io::dump(twin));
    const Result again = run("compare " + measured.string());
    ASSERT_EQ(again.code, 0) << again.output;
    const auto m = twinflow::io::read_json(measured / "compare" / "metrics.json");
    const auto number = [&](const char* key) {
      const auto* v = twinflow::io::find(m, {"particle", key});
      return v ? v->get<double>() : std::nan("");
    };
    EXPECT_DOUBLE_EQ(number("nusselt_stderr_conductivity"), 0.02 * number("nusselt"));
    EXPECT_DOUBLE_EQ(number("nusselt_stderr_with_conductivity"),
                     std::hypot(number("nusselt_stderr"), 0.02 * number("nusselt")));
    EXPECT_EQ(number("nusselt_stderr"), particle.at("nusselt_stderr").get<double>());
  }

  // A later stage's --set reaches a reused particle run: the calibrated twin changes from
  // Kapitza walls to the fluid's wall temperatures.
  const Result calibration =
      run("run " + tiny + " --set 'Compare/Calibration=wall temperatures' --out " + dir.string());
  ASSERT_EQ(calibration.code, 0) << calibration.output;
  EXPECT_NE(calibration.output.find("run: particle: inputs unchanged"), std::string::npos);
  EXPECT_EQ(calibration.output.find("Kapitza conductances"), std::string::npos)
      << calibration.output;
  EXPECT_NE(calibration.output.find("Lower wall temperature="), std::string::npos)
      << calibration.output;

  // The calibrated twin with its walls at the particle walls' effective positions: a smaller
  // domain inside the scene's box, its bins still the scene's, Navier slip at each no-slip
  // wall (Compare/Wall slip, on by default) and its heat flow compared over the scene's wall.
  // Seed 000's repulsive walls: the ideal fluid's half-space walls do not repel, so they leave
  // no depleted layer to move the walls in.
  const Result effective =
      run("run " + tiny +
          " --set 'Compare/Effective walls=true' --set Particle/Walls/Model=seed000"
          " --set Particle/Walls/Repulsion=5 --force --out " +
          dir.string());
  ASSERT_EQ(effective.code, 0) << effective.output;
  EXPECT_NE(effective.output.find("Continuum/Wall positions="), std::string::npos);
  EXPECT_NE(effective.output.find("Continuum/Slip lengths="), std::string::npos);
  const auto twin = twinflow::io::read_json(dir / "continuum_calibrated" / "summary.json");
  const auto& p = *twinflow::io::find(twin, {"continuum_parameters"});
  ASSERT_NE(twinflow::io::find(p, {"scene_box"}), nullptr) << effective.output;
  for (int d = 0; d < 2; ++d) {
    const double own = (*twinflow::io::find(p, {"box"}))[d].get<double>();
    EXPECT_LT(own, 10.0) << d; // the tiny cavity's 10 rc, less two Gibbs depths (~0.5 each)
    EXPECT_GT(own, 8.0) << d;
  }
  for (const auto& wall : (*twinflow::io::find(p, {"boundaries"})))
    for (const char* side : {"lower", "upper"})
      EXPECT_GT(twinflow::io::find(wall, {side, "slip_length"})->get<double>(), 0) << side;
  const auto m = twinflow::io::read_json(dir / "compare" / "metrics.json");
  const double area =
      twinflow::io::find(m, {"twins", "calibrated", "wall_area_over_scene"})->get<double>();
  EXPECT_GT(area, 0.8);
  EXPECT_LT(area, 1.0);
}

// `twinflow particle` records its inputs as `run` does: a later `run` of the same case reuses it.
TEST(Cli, RunReusesAParticleStageRunOnItsOwn) {
  const std::string tiny = tiny_cavity(100, 200, 0);
  const fs::path dir = fresh_dir("particle_then_run");
  const Result particle = run("particle " + tiny + " --out " + dir.string());
  ASSERT_EQ(particle.code, 0) << particle.output;
  EXPECT_TRUE(fs::exists(dir / "particle" / "inputs.json"));
  const Result all = run("run " + tiny + " --out " + dir.string());
  ASSERT_EQ(all.code, 0) << all.output;
  EXPECT_NE(all.output.find("run: particle: inputs unchanged"), std::string::npos) << all.output;
}

// A run says how it ran: summary.json records the ranks, threads per rank, decomposition, the
// host and the version; under mpirun the first console line is "R ranks x T threads".
TEST(Cli, SummarySaysHowTheRunRan) {
  const std::string tiny = tiny_cavity(100, 200, 0);
  const auto check = [](const fs::path& dir, int ranks) {
    const auto summary = twinflow::io::read_json(dir / "particle" / "summary.json");
    EXPECT_EQ(twinflow::io::number(summary, {"execution", "ranks"}), ranks);
    EXPECT_EQ(twinflow::io::number(summary, {"execution", "threads_per_rank"}), 1);
    EXPECT_EQ(twinflow::io::text(summary, {"execution", "decomposition"}),
              ranks == 1 ? "1 rank" : std::to_string(ranks) + " slabs along y");
    EXPECT_FALSE(twinflow::io::text(summary, {"provenance", "host", "cpu_model"}).empty());
    EXPECT_GE(twinflow::io::number(summary, {"provenance", "host", "cores"}), 1);
    EXPECT_FALSE(twinflow::io::text(summary, {"provenance", "host", "isa_flags"}).empty());
    EXPECT_EQ(twinflow::io::text(summary, {"provenance", "version"}).rfind("twinflow ", 0), 0u);
    EXPECT_GT(twinflow::io::number(summary, {"stage_wall_time_s"}), 0);
  };
  const fs::path one = fresh_dir("execution_one");
  const Result r1 = run("particle " + tiny + " --out " + one.string());
  ASSERT_EQ(r1.code, 0) << r1.output;
  check(one, 1);
#ifdef TWINFLOW_MPIEXEC
  const fs::path two = fresh_dir("execution_two");
  const Result r2 = run_command("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                                "OMPI_MCA_rmaps_base_oversubscribe=1 TWINFLOW_CACHE=off " +
                                std::string(TWINFLOW_MPIEXEC) + " -np 2 --bind-to none " +
                                TWINFLOW_BINARY + " particle " + tiny + " --out " + two.string());
  ASSERT_EQ(r2.code, 0) << r2.output;
  EXPECT_EQ(r2.output.rfind("twinflow: 2 ranks x 1 threads\n", 0), 0u) << r2.output;
  check(two, 2);
#endif
}

// The transport stage's independent runs (bulk runs, relaxation repeats, the heat slabs) are
// spread over the cores: its results are the same, byte for byte, whatever the threads.
TEST(Cli, TransportIsTheSameWhateverTheThreads) {
  const std::string tiny =
      std::string(TWINFLOW_SOURCE_DIR) +
      "/cases/heated_cavity_2d.prm --set 'Scene/Box size=8, 8' --set 'Scene/Density=2'"
      " --set 'Transport/Flow particles=100' --set 'Transport/Flow repeats=3'"
      " --set 'Transport/Diffusion repeats=2'";
  std::string summary[2], table[2];
  for (const int threads : {1, 2}) {
    const fs::path dir = fresh_dir("transport_threads_" + std::to_string(threads));
    const Result r = run("transport " + tiny + " --threads " + std::to_string(threads) + " --out " +
                         dir.string());
    ASSERT_EQ(r.code, 0) << r.output;
    auto j = twinflow::io::read_json(dir / "transport" / "summary.json");
    for (const char* timing : {"execution", "stage_wall_time_s", "provenance"}) j.erase(timing);
    j["results"]["measured"]["slabs"].erase("seconds");
    summary[threads - 1] = twinflow::io::dump(j);
    table[threads - 1] = twinflow::io::read_file(dir / "transport" / "coefficients.csv");
    EXPECT_NE(summary[threads - 1].find("conductivity_law"), std::string::npos);
  }
  EXPECT_EQ(table[0], table[1]);
  EXPECT_EQ(summary[0], summary[1]);
}

// Idle OpenMP threads spin briefly, then sleep (app/main.cpp): twinflow sets GOMP_SPINCOUNT=1000
// for itself unless the user chose how threads wait; bench records which way they waited.
TEST(Cli, IdleThreadsSpinBrieflyUnlessTheUserChose) {
  const auto waited = [](const std::string& env) { // "NAME=value ..." as bench recorded them
    const fs::path dir = fresh_dir("wait");
    const Result r = twinflow::testing::run_twinflow(
        "bench --set Bench/N=600 --set Bench/Scenes=ideal --set Bench/Integrators=ec-verlet "
        "--set Bench/Threads=2 --set Bench/Steps=5 --out " +
            dir.string(),
        "off", env);
    EXPECT_EQ(r.code, 0) << r.output;
    const auto summary = twinflow::io::read_json(dir / "bench" / "summary.json");
    std::string s;
    for (const auto& [name, value] : twinflow::io::find(summary, {"openmp_wait"})->items())
      s += (s.empty() ? "" : " ") + name + "=" + value.get<std::string>();
    return s;
  };
  EXPECT_EQ(waited("env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT"), "GOMP_SPINCOUNT=1000");
  EXPECT_EQ(waited("env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=passive"), "OMP_WAIT_POLICY=passive");
  EXPECT_EQ(waited("env -u OMP_WAIT_POLICY GOMP_SPINCOUNT=20"), "GOMP_SPINCOUNT=20");
}

// The transport stage's measurements are cached across run directories by what they depend on:
// another case directory with a different gravity and box reuses them (byte-identical table); a
// different fluid does not.
TEST(Cli, TransportReusesCachedMeasurementsAcrossRunDirectories) {
  const std::string base = std::string(TWINFLOW_SOURCE_DIR) +
                           "/cases/heated_cavity_2d.prm --threads 1"
                           " --set 'Transport/Measure kappa and eta=false'"
                           " --set 'Transport/Kappa from walls=false'";
  const fs::path cache = fresh_dir("cache"), a = fresh_dir("cache_a"), b = fresh_dir("cache_b"),
                 c = fresh_dir("cache_c");
  const Result first =
      twinflow::testing::run_twinflow("transport " + base + " --out " + a.string(), cache.string());
  ASSERT_EQ(first.code, 0) << first.output;
  EXPECT_EQ(first.output.find("from the cache"), std::string::npos) << first.output;
  const Result second = twinflow::testing::run_twinflow(
      "transport " + base + " --set 'Scene/Gravity=0, -0.05' --set 'Scene/Box size=30, 20' --out " +
          b.string(),
      cache.string());
  ASSERT_EQ(second.code, 0) << second.output;
  EXPECT_NE(second.output.find("reused from the cache"), std::string::npos) << second.output;
  EXPECT_EQ(twinflow::io::read_file(a / "transport" / "coefficients.csv"),
            twinflow::io::read_file(b / "transport" / "coefficients.csv"));
  const auto summary = twinflow::io::read_json(b / "transport" / "summary.json");
  EXPECT_NE(twinflow::io::find(summary, {"cache"}), nullptr);
  const Result other = twinflow::testing::run_twinflow(
      "transport " + base + " --set 'Particle/Dissipation/sigma=2' --out " + c.string(),
      cache.string());
  ASSERT_EQ(other.code, 0) << other.output;
  EXPECT_EQ(other.output.find("from the cache"), std::string::npos) << other.output;
}

// Transport/Kappa from walls: kappa is the wall run's mean heat flux over its interior slope
// (Fourier's law, recomputed here from the recorded numbers), the one the continuum twin reads;
// a scene without two thermal walls at different temperatures is an input error (exit 2).
TEST(Cli, KappaFromWallsIsFouriersLawOfTheWallRun) {
  const std::string base =
      std::string(TWINFLOW_SOURCE_DIR) +
      "/cases/heated_cavity_2d.prm --threads 1 --set 'Scene/Density=2'"
      " --set 'Transport/Measure kappa and eta=false'"
      " --set 'Transport/Kappa from walls=true' --set 'Transport/Wall steps=3000'";
  const fs::path dir = fresh_dir("kappa_walls");
  const Result r =
      twinflow::testing::run_twinflow("transport " + base + " --out " + dir.string(), "off");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto summary = twinflow::io::read_json(dir / "transport" / "summary.json");
  const auto& measured = *twinflow::io::find(summary, {"results", "measured"});
  const auto& walls = *twinflow::io::find(measured, {"walls"});
  const double kappa = twinflow::io::find(measured, {"conductivity"})->get<double>();
  EXPECT_DOUBLE_EQ(kappa, -twinflow::io::find(walls, {"heat_flux"})->get<double>() /
                              twinflow::io::find(walls, {"slope"})->get<double>());
  EXPECT_GT(twinflow::io::find(measured, {"conductivity_stderr"})->get<double>(), 0);
  EXPECT_EQ(twinflow::io::find(walls, {"particles"})->get<double>(), 4000); // 20 x 100 at density 2
  // The slope's error: the largest of the fit's (bins independent) and the blocks' slopes'
  // (20 blocks, 2 and 4 merged), which see the fluctuations the bins share.
  const auto& profile = *twinflow::io::find(walls, {"wall_profile"});
  const auto& blocking = (*twinflow::io::find(profile, {"slope_stderr_blocking"}));
  ASSERT_EQ(blocking.size(), 3u);
  double largest = twinflow::io::find(profile, {"slope_stderr_fit"})->get<double>();
  for (const auto& e : blocking) largest = std::max(largest, e.get<double>());
  EXPECT_EQ(twinflow::io::find(walls, {"slope_stderr"})->get<double>(), largest);
  const fs::path none = fresh_dir("kappa_walls_none");
  const Result bad = twinflow::testing::run_twinflow(
      "transport " + base + " --set 'Scene/x boundaries/Upper wall temperature=1.5' --out " +
          none.string(),
      "off");
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("Kappa from walls"), std::string::npos) << bad.output;
}
