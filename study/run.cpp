#include <chrono>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

#include "io/files.hpp"
#include "study/case_record.hpp"
#include "study/inputs.hpp"
#include "study/ranks.hpp"
#include "study/stages.hpp"

namespace twinflow::study {

namespace fs = std::filesystem;

// The particle scene, the fluid's coefficients, the continuum twins fed with them (nominal;
// calibrated: the walls at the temperatures the particle fluid reaches there), the comparison.
namespace {
// The last lines of a run: the verdict (compare/metrics.json) and the total wall time.
void print_ending(const fs::path& run_dir, std::chrono::steady_clock::time_point started) {
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (fs::exists(run_dir / "compare" / "metrics.json")) {
    const io::Json metrics = io::read_json(run_dir / "compare" / "metrics.json");
    if (const io::Json* verdict = io::find(metrics, {"verdict"}); verdict && verdict->is_array())
      for (const auto& line : *verdict)
        if (line.is_string()) std::cout << "run: " << line.get<std::string>() << "\n";
    std::cout << "run: report: " << fs::absolute(run_dir / "report" / "report.html").string()
              << "\n";
  }
  std::ostringstream time;
  time << std::fixed << std::setprecision(seconds < 100 ? 1 : 0) << seconds << " s";
  if (seconds >= 100)
    time << " (" << static_cast<int>(seconds) / 60 << " min " << static_cast<int>(seconds) % 60
         << " s)";
  std::cout << "run: total wall time " << time.str() << std::endl;
}
} // namespace

bool chooses_coefficient_source(const std::vector<std::string>& assignments) {
  for (const auto& a : assignments)
    if (a.rfind("Continuum/Coefficients/Source", 0) == 0) return true;
  return false;
}

namespace {
// The particle stage, kept unless its inputs changed (reused) or --force / --restart says
// otherwise: the expensive results. Checked before anything runs (bad input writes nothing).
// --restart continues what a stop left: the particle run from its checkpoint, or, when the
// particle stage had finished (the stop came later), the stages after it.
int particle_step(const Case& c, const RunOptions& options, const fs::path& run_dir, bool walls,
                  const StageInputs& particle_inputs) {
  const CaseParameters& p = c.parameters;
  const int ranks = rank_count();
  bool rerun_particle = options.force;
  if (const int rc = rank_zero_runs([&] {
        rerun_particle =
            options.force || (options.restart && fs::exists(particle_checkpoint(run_dir)));
        const bool reuse_particle =
            !rerun_particle && reusable(run_dir / "particle", particle_inputs);
        if (!reuse_particle) io::StageDirectory(run_dir, "particle", rerun_particle);
        std::cout << "run: '" << p.name << "': particle, transport, continuum"
                  << (walls ? " (nominal and calibrated)" : "") << ", compare"
                  << (ranks > 1 ? " (particle runs on " + std::to_string(ranks) + " MPI ranks)"
                                : "")
                  << (p.ensemble > 1 ? "; the particle stage an ensemble of " +
                                           std::to_string(p.ensemble) + " realisations"
                                     : "")
                  << "\n";
        return 0;
      }))
    return rc;
  rerun_particle = from_rank_zero(rerun_particle ? "rerun" : "") == "rerun";
  return run_or_reuse(
      run_dir / "particle", particle_inputs, rerun_particle,
      [&] { return particle_stage(c, options); }, Ranks::Every);
}

// The coefficients at the temperature the particle fluid has, unless the case says: its
// measured mean to 4 digits (more would be noise, ~1e-3, and would defeat the transport cache).
int take_particle_temperature(Case& c, const fs::path& run_dir) {
  CaseParameters& p = c.parameters;
  if (p.transport.temperature != 0) return 0;
  double temperature = 0;
  if (const int rc = rank_zero_runs([&] {
        const double T = io::number(io::read_json(run_dir / "particle" / "summary.json"),
                                    {"results", "T_kinetic"});
        if (T > 0) temperature = std::stod(number_text(T, 4));
        return 0;
      }))
    return rc;
  temperature = from_rank_zero(temperature);
  if (temperature > 0) {
    p.transport.temperature = temperature;
    c.record_value("Transport/Temperature", number_text(temperature, 4));
    if (on_rank_zero())
      std::cout << "run: transport at the particle fluid's mean temperature: "
                << "Transport/Temperature=" << number_text(temperature, 4) << "\n";
  }
  return 0;
}

// The transport stage: its folder is rewritten when its inputs changed, but its measurement may
// come from the transport cache (later.force would bypass that): only the user's --force
// measures again.
int transport_step(const Case& c, const RunOptions& options, const RunOptions& later,
                   const fs::path& run_dir, const StageInputs& transport_inputs) {
  RunOptions transport_options = later;
  transport_options.force = options.force;
  return run_or_reuse(
      run_dir / "transport", transport_inputs, false,
      [&] {
        if (on_rank_zero()) fs::remove(run_dir / "transport" / "summary.json"); // stale
        return transport_stage(c, transport_options);
      },
      Ranks::Every);
}

// The nominal twin stands for the particle fluid: the transport stage's coefficients, the
// particle walls' slip and jumps from theory (the user's own --set wins).
void twin_takes_the_particle_fluid(Case& c) {
  CaseParameters& p = c.parameters;
  if (chooses_coefficient_source(c.settings)) return;
  p.twin.coefficients_from_transport = true;
  c.record_value("Continuum/Coefficients/Source", "transport");
  if (p.twin.kinetic_slip_automatically) { // the slip layer replaces it where it applies
    continuum::take_kinetic_slip(p.continuum);
    p.twin.wall_slips_from_theory = true;
  }
  if (p.twin.wall_jumps_automatically) p.twin.wall_jumps_from_theory = true;
}

// The calibrated twin: a diagnostic built from the particle run's own wall measurements. When
// those make no twin (a run too short or small for its walls: a wall temperature that leaves
// the mesh unable to resolve the stratification, say), the nominal comparison still goes on.
int calibrated_step(const Case& c, const RunOptions& later, const fs::path& run_dir,
                    const StageInputs& transport_inputs, const StageInputs& particle_inputs) {
  std::optional<Case> calibrated;
  try {
    calibrated = calibrated_case(c, run_dir);
  } catch (const NoCalibratedTwin& e) {
    std::cout << "run: " << e.what() << "; going on without the calibrated twin\n";
    fs::remove_all(run_dir / "continuum_calibrated"); // compare must not read an old one
    return 0;
  }
  const StageInputs calibrated_inputs =
      stage_inputs(*calibrated, {"Scene/", "Transport/", "Continuum/"},
                   {transport_inputs.hash, particle_inputs.hash});
  return run_or_reuse(run_dir / "continuum_calibrated", calibrated_inputs, false,
                      [&] { return continuum_stage(*calibrated, later, "continuum_calibrated"); });
}
} // namespace

int run_all(Case c, const RunOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  const fs::path run_dir = run_directory(options, c.parameters.name);
  const bool walls = c.parameters.scene.has_walls() && c.parameters.scene.heat_slabs.empty();
  // Under mpirun every rank takes part in the particle runs (the particle stage, the transport
  // stage's runs); rank 0 alone runs the continuum twins and the comparison, reads and writes
  // every file and prints (study/ranks.hpp). Later stages are derived from the particle results
  // and recomputed whenever their inputs changed.
  const StageInputs particle_inputs = stage_inputs(c, {"Scene/", "Particle/"}, {});
  if (const int rc = particle_step(c, options, run_dir, walls, particle_inputs)) return rc;
  RunOptions later = options;
  later.restart = false;
  later.force = true; // derived from the particle results: recomputed when their inputs change
  later.out = run_dir;
  if (const int rc = take_particle_temperature(c, run_dir)) return rc;
  const StageInputs transport_inputs =
      stage_inputs(c, {"Scene/", "Particle/", "Transport/"}, {particle_inputs.hash},
                   transport::kMeasurementMethod);
  if (const int rc = transport_step(c, options, later, run_dir, transport_inputs)) return rc;
  twin_takes_the_particle_fluid(c);
  // From here on rank 0 alone: the twins, the comparison, the report.
  return rank_zero_runs([&] {
    write_case_record(c, run_dir); // the case the twins and the comparison take
    const StageInputs continuum_inputs =
        stage_inputs(c, {"Scene/", "Transport/", "Continuum/"}, {transport_inputs.hash});
    if (const int rc = run_or_reuse(run_dir / "continuum", continuum_inputs, false,
                                    [&] { return continuum_stage(c, later, "continuum"); }))
      return rc;
    const bool binned = fs::exists(run_dir / "particle" / "fields.h5");
    if (walls && binned)
      if (const int rc = calibrated_step(c, later, run_dir, transport_inputs, particle_inputs))
        return rc;
    if (binned) // else nothing binned to compare
      if (const int rc = compare_stage(c, run_dir)) return rc;
    print_ending(run_dir, started);
    return 0;
  });
}

} // namespace twinflow::study
