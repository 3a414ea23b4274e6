#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include <unistd.h>

#include "app/case/case.hpp"
#include "app/commands.hpp"
#include "io/field_file.hpp"
#include "particle/run.hpp"
#include "particle/simulation.hpp"
#include "transport/estimates.hpp"

namespace twinflow::app {

namespace fs = std::filesystem;

namespace {
fs::path run_directory(const CommandLine& cl, const CaseParameters& c) {
  return cl.out.empty() ? fs::path("twinflow-runs") / c.name : fs::path(cl.out);
}

// What a stage's results depend on: the case parameters of the given sections (as resolved with
// the stage's --set options) and the upstream stages' hashes. FNV-1a 64 of that, written next to
// the results as inputs.json; `run` reuses a stage whose hash is unchanged. The code revision is
// recorded beside it but not hashed: an upgrade does not throw away hours of particle data
// (`run` says when it reuses another revision's results; --force recomputes).
struct StageInputs {
  io::Json inputs = io::Json::object();
  std::string hash;
  std::map<std::string, std::string> defaults; // of the hashed parameters
};

StageInputs stage_inputs(const CommandLine& cl, std::initializer_list<const char*> sections,
                         const std::vector<std::string>& upstream_hashes, int method = 0) {
  Case c;
  c.load(cl.target, cl.overrides);
  StageInputs s;
  io::Json parameters = io::Json::object();
  const io::Json resolved = c.registry().resolved_json();
  for (const auto& [path, value] : resolved.items())
    for (const char* section : sections)
      if (path.rfind(section, 0) == 0) {
        parameters[path] = value;
        s.defaults[path] = c.registry().default_value(path);
      }
  s.inputs["parameters"] = parameters;
  s.inputs["upstream"] = io::Json::array();
  for (const auto& h : upstream_hashes) s.inputs["upstream"].push_back(h);
  if (method) s.inputs["method"] = method; // a changed measurement: not reused
  s.hash = io::content_hash(s.inputs.dump());
  const io::Json provenance = io::provenance();
  s.inputs["twinflow_git_revision"] = provenance.at("twinflow_git_revision");
  s.inputs["hash"] = s.hash;
  return s;
}

// Inputs recorded before a parameter was added lack it: the same inputs if it has its default
// (a new key does not invalidate hours of particle data), and all the others are equal.
bool same_inputs(const io::Json& recorded, const StageInputs& s) {
  const io::Json* then = io::find(recorded, {"parameters"});
  const io::Json* upstream = io::find(recorded, {"upstream"});
  if (!then || !upstream || *upstream != s.inputs.at("upstream")) return false;
  if (recorded.value("method", io::Json()) != s.inputs.value("method", io::Json())) return false;
  for (const auto& [path, value] : s.inputs.at("parameters").items()) {
    const io::Json* old = io::find(*then, {path});
    if (old ? *old != value : value.get<std::string>() != s.defaults.at(path)) return false;
  }
  return true;
}

// The stage's earlier results are complete and were made from the same inputs.
bool reusable(const fs::path& stage_dir, const StageInputs& s) {
  if (!fs::exists(stage_dir / "summary.json") || !fs::exists(stage_dir / "inputs.json"))
    return false;
  const io::Json recorded = io::read_json(stage_dir / "inputs.json");
  const std::string hash = io::text(recorded, {"hash"});
  if (hash.empty() || (hash != s.hash && !same_inputs(recorded, s))) return false;
  const std::string then = io::text(recorded, {"twinflow_git_revision"});
  const std::string now = io::text(s.inputs, {"twinflow_git_revision"});
  if (!then.empty() && !now.empty() && then != now)
    std::cout << "run: " << stage_dir.filename().string() << ": made by revision " << then
              << " (this is " << now << ")\n";
  return true;
}

// Runs a stage unless its inputs are unchanged; records its inputs after it succeeds.
template <class Stage>
int run_or_reuse(const fs::path& stage_dir, const StageInputs& s, bool force, Stage&& stage) {
  if (!force && reusable(stage_dir, s)) {
    std::cout << "run: " << stage_dir.filename().string() << ": inputs unchanged (" << s.hash
              << "), results reused\n";
    return 0;
  }
  fs::remove(stage_dir / "inputs.json"); // stale until the stage finishes again
  const int rc = stage();
  if (rc == 0) io::write_file_atomically(stage_dir / "inputs.json", io::dump(s.inputs));
  return rc;
}

} // namespace

namespace {
volatile std::sig_atomic_t stop_signal = 0;
extern "C" void on_stop_signal(int sig) {
  if (stop_signal) std::_Exit(128 + sig); // a second signal: stop now
  stop_signal = sig;
}
} // namespace

int particle_stage(const CommandLine& cl) {
  Case c;
  const CaseParameters p = c.load(cl.target, cl.overrides);
  const fs::path run_dir = run_directory(cl, p);
  const io::StageDirectory stage(run_dir, "particle", cl.force && !cl.restart);
  const fs::path checkpoint_path = stage.file("checkpoint.twfc");
  // The checkpoint belongs to these exact parameters: a changed case cannot continue it.
  const std::string parameters = c.registry().resolved_json().dump();
  std::optional<io::Checkpoint> resume;
  if (cl.restart) {
    if (!fs::exists(checkpoint_path))
      throw io::InputError(checkpoint_path.string() +
                           ": no checkpoint to restart from (was the run interrupted?)");
    resume = io::Checkpoint::read(checkpoint_path);
    if (resume->get<std::string>("case_parameters") != parameters)
      throw io::InputError(checkpoint_path.string() +
                           ": was written for other case parameters; restart with the same case "
                           "file and --set options (or start afresh with --force)");
  }
  stop_signal = 0; // from here on a signal stops the run cleanly, with a checkpoint
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  stage.create();
  if (!cl.restart) fs::remove(checkpoint_path); // a fresh run must not leave an old one behind
  const auto started = std::chrono::steady_clock::now();
  particle::RunControl control;
  control.progress = isatty(STDERR_FILENO);
  control.resume = resume ? &*resume : nullptr;
  control.checkpoint_every_seconds = 1800; // a crash loses at most half an hour
  control.stop_requested = [&] {
    return stop_signal != 0 ||
           (cl.wall_time_limit > 0 &&
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() >
                cl.wall_time_limit);
  };
  control.write_checkpoint = [&](const io::Checkpoint& state) {
    io::Checkpoint file = state;
    file.put("case_parameters", parameters);
    file.write(checkpoint_path);
  };
  particle::RunOutput out;
  try {
    out = particle::run_particles(p.particle, control);
  } catch (const particle::InstabilityError& e) {
    std::cerr << "twinflow: particle run stopped: " << e.what() << "\n";
    return 4;
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (out.interrupted) {
    std::cerr << "twinflow: particle run "
              << (stop_signal ? "interrupted by a signal" : "reached the wall-time limit")
              << " at step " << out.steps_done << "; checkpoint written to "
              << fs::absolute(checkpoint_path).string() << "\ncontinue with: twinflow particle "
              << cl.target << " --out " << run_dir.string() << " --restart\n";
    return kExitInterrupted;
  }
  io::write_file_atomically(stage.file("thermo.csv"), out.thermo_csv);
  io::write_file_atomically(stage.file("histograms.csv"), out.histograms_csv);
  io::write_file_atomically(stage.file("rdf.csv"), out.rdf_csv);
  io::write_file_atomically(stage.file("correlations.csv"), out.correlations_csv);
  io::write_file_atomically(stage.file("fields.csv"), out.fields_csv);
  io::write_file_atomically(stage.file("blocks.csv"), out.blocks_csv);
  if (!out.wall_layers_csv.empty())
    io::write_file_atomically(stage.file("wall_layers.csv"), out.wall_layers_csv);
  double max_speed = 0; // largest bin-mean speed of the final averages
  if (!out.field_snapshots.empty())
    if (const io::Field* v = out.field_snapshots.back().find("velocity"))
      for (std::size_t b = 0; b + v->components <= v->values.size(); b += v->components) {
        double s2 = 0;
        for (int d = 0; d < v->components; ++d) s2 += v->values[b + d] * v->values[b + d];
        max_speed = std::max(max_speed, std::sqrt(s2));
      }
  const io::Json convection = transport::convection_numbers(p.particle, max_speed);
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
  summary["case_file"] = fs::absolute(cl.target).string();
  summary["provenance"] = io::provenance();
  summary["results"] = out.summary;
  summary["parameters"] = c.registry().resolved_json();
  io::write_file_atomically(stage.file("summary.json"),
                            io::dump(summary)); // written last: complete
  fs::remove(checkpoint_path);                  // finished: nothing to continue
  const auto& r = out.summary;
  std::cout << "particle: N = " << io::number(r, {"N"}) << ", "
            << io::number(r, {"particle_steps_per_second"})
            << " particle-steps/s, T_kinetic = " << io::number(r, {"T_kinetic"}) << " +- "
            << io::number(r, {"T_kinetic_stderr"})
            << ", T_internal = " << io::number(r, {"T_internal"}) << " +- "
            << io::number(r, {"T_internal_stderr"})
            << ", max |dE/E| = " << io::number(r, {"energy_relative_drift_max"}) << "\n"
            << "outputs: " << fs::absolute(stage.path()).string() << "\n";
  if (!convection.is_null()) {
    const auto get = [&](const char* key) { return io::number(convection, {key}); };
    std::cout << "convection (estimates): Ra = " << get("rayleigh") << ", Pr = " << get("prandtl")
              << ", dT/T = " << get("delta_T_over_T")
              << ", g H/c^2 = " << get("stratification_g_H_over_c2")
              << ", Mach (measured) = " << get("mach_measured") << "\n";
  }
  return 0;
}

// `twinflow particle`: the stage alone, its inputs recorded as `run` records them, so that a
// later `run` of the same case reuses the particle results.
int particle_command(const CommandLine& cl) {
  Case c;
  const CaseParameters p = c.load(cl.target, cl.overrides);
  const StageInputs inputs = stage_inputs(cl, {"Scene/", "Particle/"}, {});
  const fs::path stage_dir = run_directory(cl, p) / "particle";
  const int rc = particle_stage(cl);
  if (rc == 0) io::write_file_atomically(stage_dir / "inputs.json", io::dump(inputs.inputs));
  return rc;
}

// The particle scene, the fluid's coefficients, the continuum twins fed with them (nominal;
// calibrated: the walls at the temperatures the particle fluid reaches there), the comparison.
int run_all(const CommandLine& cl) {
  Case c;
  const CaseParameters p = c.load(cl.target, cl.overrides);
  const fs::path run_dir = run_directory(cl, p);
  const bool walls = p.scene.has_walls() && !p.scene.heat_slabs.size();
  // The particle results are the expensive ones: kept unless their inputs are unchanged (reused)
  // or --force / --restart says otherwise; checked before anything runs (bad input writes
  // nothing). Later stages are derived from them and recomputed whenever their inputs changed.
  const StageInputs particle_inputs = stage_inputs(cl, {"Scene/", "Particle/"}, {});
  const bool reuse_particle =
      !cl.force && !cl.restart && reusable(run_dir / "particle", particle_inputs);
  if (!reuse_particle) io::StageDirectory(run_dir, "particle", cl.force || cl.restart);
  std::cout << "run: '" << p.name << "': particle, transport, continuum"
            << (walls ? " (nominal and calibrated)" : "") << ", compare\n";
  CommandLine later = cl;
  later.restart = false;
  later.force = true; // derived from the particle results: recomputed when their inputs change
  later.out = run_dir.string();
  if (const int rc = run_or_reuse(run_dir / "particle", particle_inputs, cl.force || cl.restart,
                                  [&] { return particle_stage(cl); }))
    return rc;
  // The coefficients at the temperature the particle fluid actually has, unless the case says.
  if (p.transport.temperature == 0) {
    const double T =
        io::number(io::read_json(run_dir / "particle" / "summary.json"), {"results", "T_kinetic"});
    if (T > 0) {
      std::ostringstream o;
      o << std::setprecision(4) << "Transport/Temperature=" << T;
      later.overrides.push_back(o.str());
      std::cout << "run: transport at the particle fluid's mean temperature: --set '" << o.str()
                << "'\n";
    }
  }
  const StageInputs transport_inputs = stage_inputs(later, {"Scene/", "Particle/", "Transport/"},
                                                    {particle_inputs.hash}, kTransportMethod);
  if (const int rc = run_or_reuse(run_dir / "transport", transport_inputs, false,
                                  [&] { return transport_stage(later); }))
    return rc;
  bool chosen = false; // the user's own choice of coefficients wins
  for (const auto& o : cl.overrides) chosen |= o.find("Continuum/Coefficients/Source") == 0;
  if (!chosen) later.overrides.push_back("Continuum/Coefficients/Source=transport");
  const StageInputs continuum_inputs =
      stage_inputs(later, {"Scene/", "Transport/", "Continuum/"}, {transport_inputs.hash});
  if (const int rc = run_or_reuse(run_dir / "continuum", continuum_inputs, false,
                                  [&] { return continuum_twin(later, "continuum"); }))
    return rc;
  if (walls && fs::exists(run_dir / "particle" / "fields.h5")) {
    CommandLine calibrated = later;
    for (const auto& o : calibrated_twin_overrides(run_dir.string(), later.overrides)) {
      std::cout << "run: calibrated twin: --set '" << o << "'\n";
      calibrated.overrides.push_back(o);
    }
    const StageInputs calibrated_inputs =
        stage_inputs(calibrated, {"Scene/", "Transport/", "Continuum/"},
                     {transport_inputs.hash, particle_inputs.hash});
    if (const int rc =
            run_or_reuse(run_dir / "continuum_calibrated", calibrated_inputs, false,
                         [&] { return continuum_twin(calibrated, "continuum_calibrated"); }))
      return rc;
  }
  if (!fs::exists(run_dir / "particle" / "fields.h5")) return 0; // nothing binned to compare
  CommandLine compare = cl;
  compare.target = run_dir.string();
  return compare_stage(compare);
}

} // namespace twinflow::app
