#include <chrono>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "compare/calibration.hpp"
#include "compare/metrics.hpp"
#include "continuum/twin_walls.hpp"
#include "io/files.hpp"
#include "study/ranks.hpp"
#include "study/stages.hpp"
#include "study/twin_model.hpp"

namespace twinflow::study {

namespace fs = std::filesystem;

namespace {
compare::TwinFacts twin_facts(const continuum::ContinuumParameters& p, double viscosity) {
  return {continuum::has_robin_walls(p.model), p.boundary[0].kapitza_inverse, viscosity};
}

// One value per wall in the case record's list form, "v0, v1, ..." (x lower, x upper, y ...).
template <class Member>
std::string wall_list(const compare::CalibratedWalls& walls, int dim, Member member) {
  std::string text;
  for (int w = 0; w < 2 * dim; ++w)
    text += (w ? ", " : "") + exact_text(member(walls.wall[w / 2][w % 2]));
  return text;
}

void record(Case& out, const std::string& path, const std::string& text) {
  out.record_value(path, text);
  std::cout << "run: calibrated twin: " << path << "=" << text << "\n";
}

// Walls without a usable jump: at the fluid's temperature beside them.
void set_wall_temperatures(const compare::CalibratedWalls& walls, Case& out) {
  CaseParameters& p = out.parameters;
  for (int d = 0; d < p.scene.dim; ++d)
    for (int side = 0; side < 2; ++side) {
      const double T = walls.wall[d][side].fluid_temperature;
      if (!std::isfinite(T)) continue;
      record(out,
             std::string("Scene/") + "xyz"[d] + " boundaries/" + (side ? "Upper" : "Lower") +
                 " wall temperature",
             exact_text(T));
      p.scene.boundary[d].temperature[side] = T;
      p.continuum.boundary[d].temperature[side] = T;
    }
}

// The measured wall positions, slip lengths and Kapitza conductances.
void set_wall_laws(const compare::CalibratedWalls& walls, Case& out) {
  CaseParameters& p = out.parameters;
  const int dim = p.scene.dim;
  if (walls.effective_positions) {
    record(out, "Continuum/Wall positions",
           wall_list(walls, dim, [](auto& w) { return w.position; }));
    std::array<double, 6> distance{};
    for (int w = 0; w < 2 * dim; ++w) distance[w] = walls.wall[w / 2][w % 2].position;
    continuum::move_walls_in(p.continuum, distance, p.scene.box);
  }
  if (walls.slip) {
    record(out, "Continuum/Slip lengths",
           wall_list(walls, dim, [](auto& w) { return w.slip_length; }));
    for (int w = 0; w < 2 * dim; ++w)
      p.continuum.boundary[w / 2].slip_length[w % 2] = walls.wall[w / 2][w % 2].slip_length;
  }
  if (walls.kapitza) {
    record(out, "Continuum/Kapitza conductances",
           wall_list(walls, dim, [](auto& w) { return w.conductance; }));
    record(out, "Continuum/Kapitza conductance errors",
           wall_list(walls, dim, [](auto& w) { return w.conductance_stderr; }));
    for (int w = 0; w < 2 * dim; ++w) {
      auto& b = p.continuum.boundary[w / 2];
      b.kapitza_conductance[w % 2] = walls.wall[w / 2][w % 2].conductance;
      b.kapitza_conductance_stderr[w % 2] = walls.wall[w / 2][w % 2].conductance_stderr;
    }
  }
}

} // namespace

Case calibrated_case(const Case& nominal, const fs::path& run_dir) {
  Case out = nominal;
  CaseParameters& p = out.parameters;
  p.twin.wall_jumps_from_theory = false; // its walls are the measured ones
  p.twin.wall_slips_from_theory = false;
  const compare::ParticleRecord run = compare::read_particle_record(run_dir, p.scene);
  double viscosity = std::nan("");
  if (p.compare.wall_slip && continuum::has_robin_walls(p.continuum.model))
    viscosity = io::number(io::read_json(run_dir / "continuum" / "summary.json",
                                         "the nominal twin runs before the calibrated one"),
                           {"continuum_parameters", "viscosity", "value_at_reference"});
  const compare::CalibratedWalls walls =
      compare::calibrate_walls(run.summary.at("results"), run.final_state(), p.scene, p.compare,
                               twin_facts(p.continuum, viscosity));
  for (const auto& note : walls.notes) std::cout << "run: calibrated twin: " << note << "\n";
  set_wall_temperatures(walls, out);
  if (p.twin.model_chosen_automatically) // the walls' epsilon may have moved past the threshold
    p.continuum.model =
        automatic_model(p.scene, p.continuum.particle_mass,
                        p.particle.conservative != particle::ConservativeForce::None,
                        p.twin.low_mach_threshold, p.twin.compressible_threshold);
  // The measured slip lengths take the walls; a re-chosen low-Mach twin has no Navier walls.
  if (walls.slip || !continuum::has_robin_walls(p.continuum.model))
    for (auto& b : p.continuum.boundary) b.kinetic_slip = {{false, false}};
  set_wall_laws(walls, out);
  try {
    continuum::check(p.continuum);
  } catch (const std::invalid_argument& e) {
    throw NoCalibratedTwin(std::string("the calibrated twin: ") + e.what());
  }
  return out;
}

void write_report(const fs::path& dir) {
  std::string quoted = "'";
  for (char ch : fs::absolute(dir).string())
    quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  quoted += "'";
  for (const char* python : {"/usr/bin/python3", "python3"}) {
    const std::string probe = std::string(python) + " -c 'import matplotlib' >/dev/null 2>&1";
    if (std::system(probe.c_str()) != 0) continue;
    const std::string command = std::string(python) + " " + TWINFLOW_REPORT_SCRIPT + " " + quoted;
    if (std::system(command.c_str()) != 0)
      std::cerr << "twinflow: the report failed (" << command << "); the results are complete\n";
    return;
  }
  std::cerr << "twinflow: no python3 with matplotlib: no figures (apt install python3-matplotlib, "
               "then python3 "
            << TWINFLOW_REPORT_SCRIPT << " " << dir.string() << ")\n";
}

int compare_stage(const Case& c, const fs::path& run_dir) {
  const auto started = std::chrono::steady_clock::now();
  const CaseParameters& p = c.parameters;
  const compare::ParticleRecord run = compare::read_particle_record(run_dir, p.scene);
  const std::vector<compare::TwinRecord> twins = compare::read_twins(run_dir, run.fields.grid);
  const io::StageDirectory stage(run_dir, "compare", true); // derived, cheap: always rewritten
  stage.create();
  compare::Comparison result = compare::compare_twins(
      run, twins, p.scene, p.compare, twin_facts(p.continuum, std::nan("")), p.name);
  result.metrics["execution"] = execution_record(p.particle.dim);
  result.metrics["stage_wall_time_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::cout << result.log.str();
  io::write_file_atomically(stage.file("bins.csv"), result.bins_csv);
  io::write_file_atomically(stage.file("profiles.csv"), result.profiles_csv);
  io::write_file_atomically(stage.file("error_vs_time.csv"), result.error_vs_time_csv);
  io::write_file_atomically(stage.file("metrics.json"), io::dump(result.metrics)); // last
  if (const io::Json* verdict = io::find(result.metrics, {"verdict"});
      verdict && verdict->is_array())
    for (const auto& line : *verdict)
      if (line.is_string()) std::cout << "compare: " << line.get<std::string>() << "\n";
  std::cout << "compare: results in " << stage.path().string()
            << " (metrics.json, bins.csv, profiles.csv, error_vs_time.csv)" << std::endl;
  write_report(run_dir);
  return 0;
}

} // namespace twinflow::study
