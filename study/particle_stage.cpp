#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <optional>

#include "io/checkpoint.hpp"
#include "io/field_file.hpp"
#include "io/files.hpp"
#include "particle/run.hpp"
#include "particle/simulation.hpp"
#include "study/ensemble.hpp"
#include "study/inputs.hpp"
#include "study/ranks.hpp"
#include "study/stability_limits.hpp"
#include "study/stages.hpp"
#include "transport/estimates.hpp"

namespace twinflow::study {

namespace fs = std::filesystem;

namespace {
volatile std::sig_atomic_t stop_signal = 0;
extern "C" void on_stop_signal(int sig) {
  if (stop_signal) std::_Exit(128 + sig); // a second signal: stop now
  stop_signal = sig;
}

// The largest bin-mean speed of the final averages.
double largest_speed(const particle::RunOutput& out) {
  double max_speed = 0;
  if (!out.field_snapshots.empty())
    if (const io::Field* v = out.field_snapshots.back().find("velocity"))
      for (std::size_t b = 0; b + v->components <= v->values.size(); b += v->components) {
        double s2 = 0;
        for (int d = 0; d < v->components; ++d) s2 += v->values[b + d] * v->values[b + d];
        max_speed = std::max(max_speed, std::sqrt(s2));
      }
  return max_speed;
}

void print_summary(const io::Json& r, const io::Json& convection, const fs::path& dir) {
  std::cout << "particle: N = " << io::number(r, {"N"}) << ", "
            << io::number(r, {"particle_steps_per_second"})
            << " particle-steps/s, T_kinetic = " << io::number(r, {"T_kinetic"}) << " +- "
            << io::number(r, {"T_kinetic_stderr"})
            << ", T_internal = " << io::number(r, {"T_internal"}) << " +- "
            << io::number(r, {"T_internal_stderr"})
            << ", max |dE/E| = " << io::number(r, {"energy_relative_drift_max"}) << "\n"
            << "outputs: " << fs::absolute(dir).string() << "\n";
  if (convection.is_null()) return;
  const auto get = [&](const char* key) { return io::number(convection, {key}); };
  std::cout << "convection (estimates): Ra = " << get("rayleigh") << ", Pr = " << get("prandtl")
            << ", dT/T = " << get("delta_T_over_T")
            << ", g H/c^2 = " << get("stratification_g_H_over_c2")
            << ", Mach (measured) = " << get("mach_measured") << "\n";
}
// "2026-11-30 17:20:05 UTC": when a checkpoint was written (printed on restart).
std::string local_time_now() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S %Z", &local);
  return buf;
}

// Every result file, summary.json last; returns the convection estimates it printed.
io::Json write_results(const Case& c, const io::StageDirectory& stage, particle::RunOutput& out,
                       double stage_seconds) {
  const CaseParameters& p = c.parameters;
  io::write_file_atomically(stage.file("thermo.csv"), out.thermo_csv);
  io::write_file_atomically(stage.file("histograms.csv"), out.histograms_csv);
  io::write_file_atomically(stage.file("rdf.csv"), out.rdf_csv);
  io::write_file_atomically(stage.file("correlations.csv"), out.correlations_csv);
  io::write_file_atomically(stage.file("fields.csv"), out.fields_csv);
  io::write_file_atomically(stage.file("blocks.csv"), out.blocks_csv);
  if (!out.wall_layers_csv.empty())
    io::write_file_atomically(stage.file("wall_layers.csv"), out.wall_layers_csv);
  const io::Json convection = transport::convection_numbers(p.particle, largest_speed(out));
  if (!convection.is_null()) out.summary["convection"] = convection;
  if (!out.field_snapshots.empty()) { // cumulative averages at a sequence of times (ParaView)
    io::FieldFile fields(stage.file("fields"), out.field_grid);
    for (auto& s : out.field_snapshots) fields.append(std::move(s));
  }
  if (!out.relaxation_csv.empty())
    io::write_file_atomically(stage.file("relaxation.csv"), out.relaxation_csv);
  if (!out.slab_profile_csv.empty())
    io::write_file_atomically(stage.file("slab_profile.csv"), out.slab_profile_csv);
  io::Json summary = io::Json::object();
  summary["stage"] = "particle";
  summary["case"] = p.name;
  summary["case_file"] = fs::absolute(c.file).string();
  summary["provenance"] = io::provenance();
  summary["execution"] = execution_record(p.particle.dim);
  summary["stage_wall_time_s"] = stage_seconds; // the run's own time: results/wall_seconds
  summary["results"] = out.summary;
  summary["parameters"] = c.record;
  io::write_file_atomically(stage.file("summary.json"), io::dump(summary)); // last: complete
  return convection;
}
} // namespace

namespace {
// The checkpoint to continue from (--restart): it belongs to these exact parameters, so that a
// changed case cannot continue it (keys that change no result, the checkpoint interval, may).
std::optional<io::Checkpoint> checkpoint_to_continue(const fs::path& checkpoint_path,
                                                     const std::string& parameters, bool root) {
  if (!fs::exists(checkpoint_path))
    throw io::InputError(checkpoint_path.string() +
                         ": no checkpoint to restart from (was the run interrupted?)");
  io::Checkpoint resume = io::Checkpoint::read(checkpoint_path);
  if (resume.get<std::string>("case_parameters") != parameters)
    throw io::InputError(checkpoint_path.string() +
                         ": was written for other case parameters; restart with the same case "
                         "file and --set options (or start afresh with --force)");
  if (root)
    std::cout << "particle: resumed from step "
              << (resume.contains("step") ? std::to_string(resume.get<std::int64_t>("step"))
                                          : std::string("?"))
              << " (checkpoint of "
              << (resume.contains("written_at") ? resume.get<std::string>("written_at")
                                                : std::string("an unknown date"))
              << ")" << std::endl;
  return resume;
}

// How the run reports, stops and checkpoints: a progress line, a signal or the wall-time limit
// stops it with a checkpoint, and one is written every Checkpoint interval.
particle::RunControl run_control(const CaseParameters& p, const RunOptions& options,
                                 const io::Checkpoint* resume, const std::string& parameters,
                                 const fs::path& checkpoint_path,
                                 std::chrono::steady_clock::time_point started) {
  particle::RunControl control;
  control.progress = particle::RunControl::progress_for_stderr();
  control.resume = resume;
  control.checkpoint_every_seconds = 60 * p.checkpoint_interval_minutes; // 0: never
  control.stop_requested = [&options, started] {
    return stop_signal != 0 ||
           (options.wall_time_limit > 0 &&
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() >
                options.wall_time_limit);
  };
  control.write_checkpoint = [parameters, checkpoint_path](const io::Checkpoint& state) {
    io::Checkpoint file = state;
    file.put("case_parameters", parameters);
    file.put("written_at", local_time_now());
    file.write(checkpoint_path);
  };
  return control;
}

// SIGINT, SIGTERM and SIGUSR1 (what a launcher passes on to its ranks, grid.cpp) to `handler`.
void handle_stop_signals(void (*handler)(int)) {
  for (const int sig : {SIGINT, SIGTERM, SIGUSR1}) std::signal(sig, handler);
}

// The stage directory made (rank 0) with the case's warnings printed, and a fresh run's old
// checkpoint removed.
void prepare_stage(const CaseParameters& p, const io::StageDirectory& stage,
                   const fs::path& checkpoint_path, bool restart) {
  for (const auto& warning : stiff_choice_warnings(p.particle, stability_limits()))
    std::cerr << "particle: " << warning << "\n";
  stage.create();
  if (!restart) fs::remove(checkpoint_path); // a fresh run leaves no old one behind
}

// write_results; when an output cannot be written the run's last checkpoint is kept, and the
// message says how to continue once there is space.
io::Json write_results_keeping_checkpoint(const Case& c, const io::StageDirectory& stage,
                                          particle::RunOutput& out, double wall_time,
                                          const fs::path& checkpoint_path,
                                          const RunOptions& options) {
  try {
    return write_results(c, stage, out, wall_time);
  } catch (const io::OutputError& e) {
    if (!fs::exists(checkpoint_path)) throw;
    throw io::OutputError(
        std::string(e.what()) +
        "; the run's last checkpoint is kept: free the "
        "space and continue with: " +
        (options.continue_command.empty() ? std::string("--restart") : options.continue_command));
  }
}

int report_interrupted(const Case& c, const RunOptions& options, const fs::path& run_dir,
                       const fs::path& checkpoint_path, long steps_done) {
  std::cerr << "twinflow: particle run "
            << (stop_signal ? "interrupted by a signal" : "reached the wall-time limit")
            << " at step " << steps_done << "; checkpoint written to "
            << fs::absolute(checkpoint_path).string() << "\ncontinue with: "
            << (options.continue_command.empty()
                    ? "twinflow particle " + c.file + " --out " + run_dir.string() + " --restart"
                    : options.continue_command)
            << "\n";
  return kExitInterrupted;
}
} // namespace

int particle_run(const Case& c, const RunOptions& options, const io::StageDirectory& stage,
                 const fs::path& checkpoint_path, bool restart) {
  const CaseParameters& p = c.parameters;
  // Under mpirun the particles are split over the ranks (particle/decomposition.hpp); rank 0
  // writes every file, the checkpoint included.
  const int ranks = particle::Slabs::world_size();
  const bool root = particle::Slabs::world_rank() == 0;
  const std::string parameters = without_keys_that_change_no_result(c.record).dump();
  std::optional<io::Checkpoint> resume;
  if (restart) resume = checkpoint_to_continue(checkpoint_path, parameters, root);
  stop_signal = 0; // from here on a signal stops the run cleanly, with a checkpoint
  handle_stop_signals(on_stop_signal);
  if (root) prepare_stage(p, stage, checkpoint_path, restart);
  if (ranks > 1) MPI_Barrier(MPI_COMM_WORLD);
  const auto started = std::chrono::steady_clock::now();
  const particle::RunControl control =
      run_control(p, options, resume ? &*resume : nullptr, parameters, checkpoint_path, started);
  particle::RunOutput out;
  try {
    out = particle::run_particles(p.particle, control);
  } catch (const particle::InstabilityError& e) {
    // One write, so that under mpirun the launcher's own lines cannot land inside it.
    std::cerr << "twinflow: particle run stopped: " + std::string(e.what()) + "\n" << std::flush;
    if (ranks > 1) MPI_Abort(MPI_COMM_WORLD, kExitUnstable); // the other ranks wait for this one
    return kExitUnstable;
  }
  handle_stop_signals(SIG_DFL);
  if (!root) return out.interrupted ? kExitInterrupted : 0;
  if (out.interrupted)
    return report_interrupted(c, options, run_directory(options, p.name), checkpoint_path,
                              out.steps_done);
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const io::Json convection =
      write_results_keeping_checkpoint(c, stage, out, wall_time, checkpoint_path, options);
  fs::remove(checkpoint_path); // finished: nothing to continue
  print_summary(out.summary, convection, stage.path());
  return 0;
}

int particle_stage(const Case& c, const RunOptions& options) {
  if (c.parameters.ensemble > 1) return ensemble_particle_stage(c, options);
  const fs::path run_dir = run_directory(options, c.parameters.name);
  const io::StageDirectory stage(run_dir, "particle", options.force && !options.restart);
  return particle_run(c, options, stage, particle_checkpoint(run_dir), options.restart);
}

int particle_command(const Case& c, const RunOptions& options) {
  const StageInputs inputs = stage_inputs(c, {"Scene/", "Particle/"}, {});
  const int rc = particle_stage(c, options);
  if (rc == 0 && particle::Slabs::world_rank() == 0)
    io::write_file_atomically(run_directory(options, c.parameters.name) / "particle" /
                                  "inputs.json",
                              io::dump(inputs.inputs));
  return rc;
}

} // namespace twinflow::study
