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

namespace twinflow::study {

namespace fs = std::filesystem;

namespace {
compare::TwinFacts twin_facts(const continuum::ContinuumParameters& p, double viscosity) {
  return {continuum::has_robin_walls(p.model), p.boundary[0].kapitza_inverse, viscosity};
}

} // namespace

Case calibrated_case(const Case& nominal, const fs::path& run_dir) {
  Case out = nominal;
  CaseParameters& p = out.parameters;
  p.twin.wall_jumps_from_theory = false; // its walls are the measured ones
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
  // Each value as recorded, so that the record reproduces the twin.
  const int dim = p.scene.dim;
  const auto list = [&](auto member, int digits) {
    std::string text;
    std::array<double, 6> values{};
    for (int w = 0; w < 2 * dim; ++w) {
      const std::string v = number_text(member(walls.wall[w / 2][w % 2]), digits);
      values[w] = std::stod(v);
      text += (w ? ", " : "") + v;
    }
    return std::pair{text, values};
  };
  const auto set = [&](const std::string& path, const std::string& text) {
    out.record_value(path, text);
    std::cout << "run: calibrated twin: " << path << "=" << text << "\n";
  };
  for (int d = 0; d < dim; ++d)
    for (int side = 0; side < 2; ++side) {
      const double T = walls.wall[d][side].fluid_temperature;
      if (!std::isfinite(T)) continue;
      const std::string text = number_text(T, 10);
      set(std::string("Scene/") + "xyz"[d] + " boundaries/" + (side ? "Upper" : "Lower") +
              " wall temperature",
          text);
      p.scene.boundary[d].temperature[side] = std::stod(text);
      p.continuum.boundary[d].temperature[side] = std::stod(text);
    }
  if (p.twin.model_chosen_automatically) // the walls' epsilon may have moved past the threshold
    p.continuum.model =
        automatic_model(p.scene, p.continuum.particle_mass,
                        p.particle.conservative != particle::ConservativeForce::None,
                        p.twin.low_mach_threshold, p.twin.compressible_threshold);
  // The measured slip lengths take the walls; a re-chosen low-Mach twin has no Navier walls.
  if (walls.slip || !continuum::has_robin_walls(p.continuum.model))
    for (auto& b : p.continuum.boundary) b.kinetic_slip = {{false, false}};
  if (walls.effective_positions) {
    const auto [text, distance] = list([](const auto& w) { return w.position; }, 6);
    set("Continuum/Wall positions", text);
    continuum::move_walls_in(p.continuum, distance, p.scene.box);
  }
  if (walls.slip) {
    const auto [text, b] = list([](const auto& w) { return w.slip_length; }, 6);
    set("Continuum/Slip lengths", text);
    for (int w = 0; w < 2 * dim; ++w) p.continuum.boundary[w / 2].slip_length[w % 2] = b[w];
  }
  if (walls.kapitza) {
    const auto [text, h] = list([](const auto& w) { return w.conductance; }, 8);
    const auto [error_text, h_stderr] = list([](const auto& w) { return w.conductance_stderr; }, 4);
    set("Continuum/Kapitza conductances", text);
    set("Continuum/Kapitza conductance errors", error_text);
    for (int w = 0; w < 2 * dim; ++w) {
      p.continuum.boundary[w / 2].kapitza_conductance[w % 2] = h[w];
      p.continuum.boundary[w / 2].kapitza_conductance_stderr[w % 2] = h_stderr[w];
    }
  }
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
