#include <chrono>
#include <filesystem>
#include <iostream>

#include <unistd.h>

#include "app/case/case.hpp"
#include "app/commands.hpp"
#include "io/field_file.hpp"
#include "particle/run.hpp"
#include "particle/simulation.hpp"

namespace twinflow::app {

namespace fs = std::filesystem;

namespace {
fs::path run_directory(const CommandLine& cl, const CaseParameters& c) {
  return cl.out.empty() ? fs::path("twinflow-runs") / c.name : fs::path(cl.out);
}

} // namespace

int particle_stage(const CommandLine& cl) {
  Case c;
  const CaseParameters p = c.load(cl.target, cl.overrides);
  const fs::path run_dir = run_directory(cl, p);
  const io::StageDirectory stage(run_dir, "particle", cl.force);
  stage.create();
  particle::RunControl control;
  control.progress = isatty(STDERR_FILENO);
  particle::RunOutput out;
  try {
    out = particle::run_particles(p.particle, control);
  } catch (const particle::InstabilityError& e) {
    std::cerr << "twinflow: particle run stopped: " << e.what() << "\n";
    return 4;
  }
  io::write_file_atomically(stage.file("thermo.csv"), out.thermo_csv);
  io::write_file_atomically(stage.file("histograms.csv"), out.histograms_csv);
  io::write_file_atomically(stage.file("rdf.csv"), out.rdf_csv);
  io::write_file_atomically(stage.file("correlations.csv"), out.correlations_csv);
  io::write_file_atomically(stage.file("fields.csv"), out.fields_csv);
  if (!out.field_snapshots.empty()) { // cumulative averages at a sequence of times (ParaView)
    io::FieldFile fields(stage.file("fields"), out.field_grid);
    for (auto& s : out.field_snapshots) fields.append(std::move(s));
  }
  if (!out.slab_profile_csv.empty())
    io::write_file_atomically(stage.file("slab_profile.csv"), out.slab_profile_csv);
  io::Json summary = io::Json::object();
  summary["stage"] = "particle";
  summary["case"] = p.name;
  summary["case_file"] = fs::absolute(cl.target).string();
  summary["provenance"] = io::provenance();
  summary["results"] = out.summary;
  summary["parameters"] = c.registry().resolved_json();
  io::write_file_atomically(stage.file("summary.json"), summary.dump()); // written last: complete
  const auto& r = out.summary;
  std::cout << "particle: N = " << r.find("N")->number() << ", "
            << r.find("particle_steps_per_second")->number()
            << " particle-steps/s, T_kinetic = " << r.find("T_kinetic")->number() << " +- "
            << r.find("T_kinetic_stderr")->number()
            << ", T_internal = " << r.find("T_internal")->number() << " +- "
            << r.find("T_internal_stderr")->number()
            << ", max |dE/E| = " << r.find("energy_relative_drift_max")->number() << "\n"
            << "outputs: " << fs::absolute(stage.path()).string() << "\n";
  return 0;
}

int run_all(const CommandLine& cl) {
  Case c;
  const CaseParameters p = c.load(cl.target, cl.overrides);
  const io::StageDirectory stage(run_directory(cl, p), "particle", cl.force);
  std::cout << "run: the particle stage of '" << p.name
            << "' (pairing with the transport and continuum stages comes with the study issue; "
               "run `twinflow transport` and `twinflow continuum` on their own meanwhile)\n";
  return particle_stage(cl);
}

} // namespace twinflow::app
