// twinflow bench: particle-steps/s of the particle core per integrator, scene, size and threads,
// and (Bench/Thermo) the energy drift, temperatures and pressure of the same system.
//
// Without --set 'Bench/...' keys it runs the whole matrix below. Keys (comma-separated lists):
//   Bench/N=6000,48000        3D sizes; the box is 2L x L x L with L = (N / (2 rho))^(1/3)
//   Bench/N2D=48000           2D sizes; the box is 2L x L with L = (N / (2 rho))^(1/2)
//   Bench/Scenes=a0=15+heat   ideal | ideal+heat | a0=15 | a0=15+heat
//   Bench/Integrators=shardlow,ec-verlet
//   Bench/Threads=1,2         OpenMP thread counts
//   Bench/Skin=0.2            pair-list skins (Particle/Neighbour skin; default its default)
//   Bench/Noise=gaussian      pair noises: gaussian | uniform (Particle/Noise)
//   Bench/Steps=200           timed steps (default max(5, 3e6 / N))
//   Bench/Thermo=1000         instead of timing: equilibrate 1000 steps, then sample as many,
//                             printing energy drift, T_kinetic, T_internal and pressure
//   Bench/Cavity=1600,6400    the default cavity (its fluid, walls and gravity) at these N in a
//                             square box, beside the same fluid periodic: what the walls cost

#include <omp.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <sstream>

#include "io/files.hpp"
#include "particle/decomposition.hpp"
#include "particle/run.hpp"
#include "study/bench.hpp"
#include "study/ranks.hpp"

namespace twinflow::study {

namespace {
using namespace particle;

struct Scene {
  const char* name;
  bool repulsion, heat;
};

const Scene all_scenes[] = {{"ideal", false, false},
                            {"ideal+heat", false, true},
                            {"a0=15", true, false},
                            {"a0=15+heat", true, true}};

// LAMMPS's DPDE system (bench/in.dpde_bench.lmp): rho = 3, rc = 1, sigma = 3, c_v = 200, kappa =
// 40, w_C = w_R = 1 - r, w_D = w_H = (1 - r)^2 (LAMMPS's single weight w = 1 - r), inverse heat law
// with constant kappa, dt = 0.005.
ParticleParameters bench_case(int dim, std::array<double, 3> box, const Scene& s, Integrator i) {
  ParticleParameters p;
  p.dim = dim;
  p.box = box;
  p.density = 3;
  p.dt = 0.005;
  p.integrator = i;
  p.sigma = 3;
  p.cv = 200;
  p.dissipation = {1.0, 2.0};
  p.heat_weight = {1.0, 2.0};
  p.conservative = s.repulsion ? ConservativeForce::Constant : ConservativeForce::None;
  p.a0 = 15;
  p.heat = s.heat ? HeatLaw::Inverse : HeatLaw::None;
  p.heat_coefficient = HeatCoefficient::Constant;
  p.kappa0 = 40;
  p.initial_internal_energy = InitialInternalEnergy::Theta; // the deck's theta_i = T0
  return p;
}

struct Size {
  int dim;
  std::array<double, 3> box;
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

long peak_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

struct Options {
  std::vector<Size> sizes{
      {3, {{20, 10, 10}}}, {3, {{40, 20, 20}}}, {3, {{80, 40, 40}}}, {2, {{160, 100, 1}}}};
  std::vector<const Scene*> scenes{&all_scenes[0], &all_scenes[1], &all_scenes[2], &all_scenes[3]};
  std::vector<Integrator> integrators{Integrator::Shardlow, Integrator::EcVerlet,
                                      Integrator::Euler};
  std::vector<int> threads;
  std::vector<double> skins{ParticleParameters().neighbour_skin};
  std::vector<bool> uniform_noise{false};
  bool sizes_given = false;
  long steps = 0;                 // 0: max(5, 3e6 / N)
  long thermo = 0;                // > 0: thermodynamics instead of timing
  std::vector<long> cavity_sizes; // Bench/Cavity: the default cavity walled and periodic
};

using Bad = std::function<io::InputError(const std::string& allowed)>;

void parse_sizes(Options& o, const std::string& key, const std::string& value, const Bad& bad) {
  if (!o.sizes_given) o.sizes.clear(); // the default matrix
  o.sizes_given = true;
  for (const auto& n : split(value)) {
    if (key == "Bench/N2D") { // rho = 3, box 2L x L
      const double l = std::sqrt(std::stod(n) / (2 * 3.0));
      if (!(l >= 4)) throw bad("N >= 96");
      o.sizes.push_back({2, {{2 * l, l, 1}}});
      continue;
    }
    const double l = std::cbrt(std::stod(n) / (2 * 3.0)); // rho = 3, box 2L x L x L
    if (!(l >= 4)) throw bad("N >= 384");
    o.sizes.push_back({3, {{2 * l, l, l}}});
  }
}

void parse_scenes(Options& o, const std::string& value, const Bad& bad) {
  o.scenes.clear();
  for (const auto& name : split(value)) {
    const Scene* found = nullptr;
    for (const auto& s : all_scenes)
      if (name == s.name) found = &s;
    if (!found) throw bad("ideal, ideal+heat, a0=15, a0=15+heat");
    o.scenes.push_back(found);
  }
}

void parse_integrators(Options& o, const std::string& value, const Bad& bad) {
  o.integrators.clear();
  for (const auto& name : split(value)) {
    if (name == "shardlow")
      o.integrators.push_back(Integrator::Shardlow);
    else if (name == "ec-verlet")
      o.integrators.push_back(Integrator::EcVerlet);
    else if (name == "euler")
      o.integrators.push_back(Integrator::Euler);
    else
      throw bad("shardlow, ec-verlet, euler");
  }
}

void parse_cavity(Options& o, const std::string& value, const Bad& bad) {
  for (const auto& n : split(value)) {
    o.cavity_sizes.push_back(std::stol(n));
    if (o.cavity_sizes.back() < 64) throw bad("N >= 64");
  }
  if (!o.sizes_given) o.sizes.clear(); // the cavity alone unless sizes are given too
  o.sizes_given = true;
}

// One --set 'Bench/KEY=VALUE' into the options.
void parse_setting(Options& o, const std::string& key, const std::string& value, const Bad& bad) {
  if (key == "Bench/N" || key == "Bench/N2D") {
    parse_sizes(o, key, value, bad);
  } else if (key == "Bench/Scenes") {
    parse_scenes(o, value, bad);
  } else if (key == "Bench/Integrators") {
    parse_integrators(o, value, bad);
  } else if (key == "Bench/Threads") {
    o.threads.clear();
    for (const auto& t : split(value)) {
      o.threads.push_back(std::stoi(t));
      if (o.threads.back() < 1) throw bad("threads >= 1");
    }
  } else if (key == "Bench/Skin") {
    o.skins.clear();
    for (const auto& t : split(value)) {
      o.skins.push_back(std::stod(t));
      if (!(o.skins.back() >= 0 && o.skins.back() < 1)) throw bad("skins in [0, 1)");
    }
  } else if (key == "Bench/Noise") {
    o.uniform_noise.clear();
    for (const auto& t : split(value)) {
      if (t != "gaussian" && t != "uniform") throw bad("gaussian, uniform");
      o.uniform_noise.push_back(t == "uniform");
    }
  } else if (key == "Bench/Steps") {
    o.steps = std::stol(value);
    if (o.steps < 1) throw bad("steps >= 1");
  } else if (key == "Bench/Cavity") {
    parse_cavity(o, value, bad);
  } else if (key == "Bench/Thermo") {
    o.thermo = std::stol(value);
    if (o.thermo < 10) throw bad("steps >= 10");
  } else {
    throw bad("Bench/N, Bench/N2D, Bench/Scenes, Bench/Integrators, Bench/Threads, Bench/Skin, "
              "Bench/Noise, Bench/Steps, Bench/Thermo, Bench/Cavity");
  }
}

Options parse(const RunOptions& cl, const std::vector<std::string>& settings) {
  Options o;
  const int max_threads = cl.threads > 0 ? cl.threads : omp_get_num_procs();
  for (int t = 1; t <= std::min(2, max_threads); ++t) o.threads.push_back(t);
  for (const auto& setting : settings) {
    const auto eq = setting.find('=');
    const Bad bad = [&](const std::string& allowed) {
      return io::InputError("--set '" + setting + "': allowed: " + allowed);
    };
    if (eq == std::string::npos) throw bad("Bench/KEY=VALUE");
    try {
      parse_setting(o, setting.substr(0, eq), setting.substr(eq + 1), bad);
    } catch (const std::logic_error&) { // stoi/stod
      throw bad("numbers");
    }
  }
  return o;
}
// The default cavity's fluid at N particles in a square box (its density): with its walls and
// gravity, or periodic without them.
ParticleParameters cavity_case(const ParticleParameters& cavity, long n, bool walls) {
  ParticleParameters p = cavity;
  const double l = std::sqrt(n / p.density);
  p.box = {{l, l, l}};
  if (!walls) {
    for (auto& w : p.walls) w.present = false;
    p.gravity = {{0, 0, 0}};
  }
  return p;
}

// What a row ran: the scene, integrator, threads and settings.
void describe_row(const ParticleParameters& p, const std::string& scene, int threads,
                  io::Json& row) {
  row["dim"] = p.dim;
  row["scene"] = scene;
  row["integrator"] = to_string(p.integrator);
  row["threads"] = threads;
  row["skin"] = p.neighbour_skin;
  row["noise"] = p.uniform_noise ? "uniform" : "gaussian";
}

// One timed row: particle-steps/s of `p` over `steps` steps.
std::string timed_row(const ParticleParameters& p, const std::string& scene, int threads,
                      long steps_given, io::Json& row) {
  const long steps = steps_given > 0 ? steps_given : std::max(5L, 3000000L / p.particle_count());
  const BenchResult r = bench_particles(p, steps);
  char line[512];
  std::snprintf(line, sizeof line,
                "| %d | %ld | %s | %s | %d | %g | %s | %.3g | %.1f | %ld | %d | %.0f |\n", p.dim,
                r.particles, scene.c_str(), to_string(p.integrator), threads, p.neighbour_skin,
                p.uniform_noise ? "uniform" : "gaussian", r.particle_steps_per_second,
                r.steps_per_list, peak_rss_kb(), r.ranks, r.bytes_per_particle);
  row["ranks"] = r.ranks;
  row["bytes_per_particle"] = r.bytes_per_particle;
  row["ghosts_per_owned"] = r.ghosts_per_owned;
  row["steps_per_list"] = r.steps_per_list;
  row["N"] = r.particles;
  row["steps"] = steps;
  row["seconds"] = r.seconds;
  row["particle_steps_per_second"] = r.particle_steps_per_second;
  row["peak_rss_kb"] = peak_rss_kb();
  describe_row(p, scene, threads, row);
  return line;
}

// Instead of timing: equilibrate and sample `steps` steps each, the thermodynamics as one row.
std::string thermo_row(ParticleParameters p, const std::string& scene, int threads, long steps,
                       io::Json& row) {
  p.equilibration_steps = steps;
  p.steps = steps;
  p.sample_interval = std::max(1L, steps / 200);
  const io::Json s = run_particles(p).summary;
  auto num = [&](const char* k) { return io::number(s, {k}); };
  char line[512];
  std::snprintf(line, sizeof line,
                "| %d | %ld | %s | %s | %d | %g | %s | %ld | %.2e | %.5f +- %.5f | %.5f +- %.5f | "
                "%.4f +- %.4f |\n",
                p.dim, p.particle_count(), scene.c_str(), to_string(p.integrator), threads,
                p.neighbour_skin, p.uniform_noise ? "uniform" : "gaussian", 2 * steps,
                num("energy_relative_drift_max"), num("T_kinetic"), num("T_kinetic_stderr"),
                num("T_internal"), num("T_internal_stderr"), num("pressure"),
                num("pressure_stderr"));
  row = s;
  describe_row(p, scene, threads, row);
  return line;
}

std::string table_header(bool thermo) {
  if (thermo)
    return "| dim | N | scene | integrator | threads | skin | noise | steps | max dE/E0 | "
           "T_kinetic | T_internal | pressure "
           "|\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  return "| dim | N | scene | integrator | threads | skin | noise | particle-steps/s | steps per "
         "list | peak RSS kB | MPI ranks | array bytes per particle "
         "|\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
}

// The table so far and the rows, printed as they come (rank 0) and kept for the files.
struct Rows {
  bool root = particle::Slabs::world_rank() == 0; // under mpirun every rank runs each point
  std::ostringstream table;
  io::Json json = io::Json::array();
  void add(const std::string& line, io::Json row) {
    if (root) std::cout << line << std::flush;
    table << line;
    json.push_back(std::move(row));
  }
};

// Every point of the matrix: sizes x scenes x integrators x threads x skins x noises.
void bench_matrix(const Options& o, Rows& rows) {
  for (const auto& size : o.sizes)
    for (const Scene* scene : o.scenes)
      for (const auto integrator : o.integrators)
        for (const int threads : o.threads)
          for (const double skin : o.skins)
            for (const bool uniform : o.uniform_noise) {
              omp_set_num_threads(threads);
              auto p = bench_case(size.dim, size.box, *scene, integrator);
              p.neighbour_skin = skin;
              p.uniform_noise = uniform;
              io::Json row = io::Json::object();
              const std::string line = o.thermo > 0
                                           ? thermo_row(p, scene->name, threads, o.thermo, row)
                                           : timed_row(p, scene->name, threads, o.steps, row);
              rows.add(line, std::move(row));
            }
}

// The walls' cost: the cavity walled beside its fluid periodic, at each N and thread count,
// interleaved (walled, bulk, walled, bulk, ...).
void bench_cavity(const Options& o, const ParticleParameters& cavity, Rows& rows) {
  for (const long n : o.cavity_sizes)
    for (const int threads : o.threads)
      for (const bool walls : {true, false}) {
        omp_set_num_threads(threads);
        io::Json row = io::Json::object();
        const std::string line =
            timed_row(cavity_case(cavity, n, walls), walls ? "cavity walled" : "cavity bulk",
                      threads, o.steps, row);
        rows.add(line, std::move(row));
      }
}

void write_bench(const io::StageDirectory& stage, const Rows& rows) {
  stage.create();
  io::Json summary = io::Json::object();
  summary["stage"] = "bench";
  summary["provenance"] = io::provenance();
  summary["ranks"] = rank_count(); // the threads: per row
  // How idle threads waited: the front end's default (app/main.cpp) or the user's choice.
  io::Json wait = io::Json::object();
  for (const char* name : {"OMP_WAIT_POLICY", "GOMP_SPINCOUNT"})
    if (const char* value = std::getenv(name)) wait[name] = std::string(value);
  summary["openmp_wait"] = wait;
  summary["results"] = rows.json;
  io::write_file_atomically(stage.file("bench.md"), rows.table.str());
  io::write_file_atomically(stage.file("summary.json"), io::dump(summary));
  std::cout << "outputs: " << std::filesystem::absolute(stage.path()).string() << "\n";
}
} // namespace

int bench(const RunOptions& cl, const std::vector<std::string>& settings,
          const ParticleParameters& cavity) {
  const io::StageDirectory stage(
      cl.out.empty() ? std::filesystem::path("twinflow-runs/bench") : cl.out, "bench", cl.force);
  const Options o = parse(cl, settings);
  Rows rows;
  const std::string header = table_header(o.thermo > 0);
  if (rows.root) std::cout << header << std::flush;
  rows.table << header;
  bench_matrix(o, rows);
  bench_cavity(o, cavity, rows);
  if (rows.root) write_bench(stage, rows);
  return 0;
}

} // namespace twinflow::study
