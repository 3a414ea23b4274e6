// twinflow bench: particle-steps/s of the particle core per integrator, scene, size and threads.

#include <omp.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "app/commands.hpp"
#include "io/files.hpp"
#include "particle/run.hpp"

namespace twinflow::app {

namespace {
using namespace particle;

struct Scene {
  const char* name;
  bool repulsion, heat;
};

// LAMMPS's DPDE system (shared/peers/lammps): rho = 3, rc = 1, sigma = 3, c_v = 200,
// w_D = w_H = (1 - r)^2 (LAMMPS's single weight w = 1 - r), inverse heat law, dt = 0.005.
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
  return p;
}
} // namespace

int bench(const CommandLine& cl) {
  const io::StageDirectory stage(cl.out.empty() ? std::filesystem::path("twinflow-runs/bench")
                                                : std::filesystem::path(cl.out),
                                 "bench", cl.force);
  const Scene scenes[] = {{"ideal", false, false},
                          {"ideal+heat", false, true},
                          {"a0=15", true, false},
                          {"a0=15+heat", true, true}};
  struct Size {
    int dim;
    std::array<double, 3> box;
  };
  const Size sizes[] = {
      {3, {{20, 10, 10}}}, {3, {{40, 20, 20}}}, {3, {{80, 40, 40}}}, {2, {{160, 100, 1}}}};
  const int max_threads = cl.threads > 0 ? cl.threads : omp_get_num_procs();
  std::ostringstream table;
  table << "| dim | N | scene | integrator | threads | particle-steps/s | bytes/particle |\n"
           "|---|---|---|---|---|---|---|\n";
  std::cout << table.str() << std::flush;
  io::Json rows = io::Json::array();
  for (const auto& size : sizes)
    for (const auto& scene : scenes)
      for (const auto integrator : {Integrator::Shardlow, Integrator::EcVerlet, Integrator::Euler})
        for (int threads = 1; threads <= std::min(2, max_threads); ++threads) {
          omp_set_num_threads(threads);
          const auto p = bench_case(size.dim, size.box, scene, integrator);
          const long steps = std::max(5L, 3000000L / p.particle_count());
          const BenchResult r = bench_particles(p, steps);
          char line[256];
          std::snprintf(line, sizeof line, "| %d | %ld | %s | %s | %d | %.3g | %.0f |\n", size.dim,
                        r.particles, scene.name, to_string(integrator), threads,
                        r.particle_steps_per_second, r.bytes_per_particle);
          std::cout << line << std::flush;
          table << line;
          io::Json row = io::Json::object();
          row["dim"] = size.dim;
          row["N"] = r.particles;
          row["scene"] = scene.name;
          row["integrator"] = to_string(integrator);
          row["threads"] = threads;
          row["steps"] = steps;
          row["seconds"] = r.seconds;
          row["particle_steps_per_second"] = r.particle_steps_per_second;
          row["bytes_per_particle"] = r.bytes_per_particle;
          rows.push_back(row);
        }
  stage.create();
  io::Json summary = io::Json::object();
  summary["stage"] = "bench";
  summary["provenance"] = io::provenance();
  summary["results"] = rows;
  io::write_file_atomically(stage.file("bench.md"), table.str());
  io::write_file_atomically(stage.file("summary.json"), summary.dump());
  std::cout << "outputs: " << std::filesystem::absolute(stage.path()).string() << "\n";
  return 0;
}

} // namespace twinflow::app
