#include "study/case_record.hpp"

#include "io/files.hpp"
#include "io/json_fields.hpp"

// Every member of every parameter struct, in declaration order (checked at compile time).
namespace twinflow::scene {
TWINFLOW_JSON_FIELDS(DirectionBoundary, periodic, thermal, temperature, no_slip)
TWINFLOW_JSON_FIELDS(HeatSlab, direction, lower, upper, power)
TWINFLOW_JSON_FIELDS(SceneParameters, dim, box, density, temperature, temperature_perturbation,
                     shear_perturbation, poiseuille_force, gravity, boundary, heat_slabs, bins)
} // namespace twinflow::scene

namespace twinflow::particle {
TWINFLOW_JSON_FIELDS(WeightParameters, cutoff, exponent)
TWINFLOW_JSON_FIELDS(HeatSlab, direction, lower, upper, power)
TWINFLOW_JSON_FIELDS(WallPair, present, thermal, temperature, no_slip, model, conduction)
TWINFLOW_JSON_FIELDS(ParticleParameters, dim, box, density, mass, seed, integrator, energy_offset,
                     dt, neighbour_skin, uniform_noise, equilibration_steps, steps, temperature,
                     temperature_perturbation, shear_perturbation, poiseuille_force,
                     initial_velocities, initial_internal_energy, energy, cv, conservative, a0,
                     conservative_cutoff, reference_temperature, friction, sigma, gamma,
                     dissipation, heat, heat_coefficient, kappa0, heat_weight, linear_noise_factor,
                     heat_slabs, walls, wall_a0, wall_range, wall_density, wall_diffuse, gravity,
                     bins, sample_interval, blocks, histogram_bins, rdf_bins, correlation_samples)
} // namespace twinflow::particle

namespace twinflow::transport {
TWINFLOW_JSON_FIELDS(TransportParameters, source, measure_flows, temperature, flow_particles,
                     flow_repeats, diffusion_repeats, temperature_spread, kappa_from_slabs,
                     viscosity_along_isobar, kappa_from_walls, wall_steps)
} // namespace twinflow::transport

namespace twinflow::continuum {
TWINFLOW_JSON_FIELDS(EquationOfState, b0, b1, b2, n_ref)
TWINFLOW_JSON_FIELDS(PowerLaw, value_at_reference, exponent, sutherland_temperature, pair_fraction,
                     pair_exponent)
TWINFLOW_JSON_FIELDS(DirectionBoundary, periodic, fixed_temperature, temperature, heat_flux,
                     no_slip, kapitza_conductance, kapitza_inverse, kapitza_conductance_stderr,
                     slip_length, kinetic_slip, pinned_depth)
TWINFLOW_JSON_FIELDS(WallFriction, wall_density, tangent_moment, gamma_constant, gamma_inverse,
                     diffuse)
TWINFLOW_JSON_FIELDS(HeatSlab, direction, lower, upper, power)
TWINFLOW_JSON_FIELDS(ContinuumParameters, dim, box, model, boundary, gravity, number_density,
                     particle_count, particle_mass, heat_capacity, thermal_expansion,
                     reference_temperature, viscosity, conductivity, wall_friction, heat_slabs,
                     equation_of_state, bulk_viscosity, cells, refinements, newton_tolerance,
                     max_newton_iterations, continuation_start_rayleigh, linear_solver, mode,
                     end_time, time_step, theta, initial_temperature, snapshot_times,
                     snapshot_every, series_every, bins, bin_lower, bin_box, probe_points,
                     profile_samples, write_fields)
} // namespace twinflow::continuum

namespace twinflow::compare {
TWINFLOW_JSON_FIELDS(CompareParameters, wall_layer, calibration, effective_walls, wall_slip,
                     rayleigh_control)
} // namespace twinflow::compare

namespace twinflow::study {
TWINFLOW_JSON_FIELDS(StabilityBounds, energy_drift, temperature_tolerance, fluctuation_number)
TWINFLOW_JSON_FIELDS(TwinChoice, coefficients_from_transport, model_chosen_automatically,
                     kinetic_slip_automatically, wall_jumps_automatically, wall_jumps_from_theory,
                     wall_slips_from_theory, low_mach_threshold, compressible_threshold)
TWINFLOW_JSON_FIELDS(CaseParameters, name, scene, particle, transport, continuum, twin,
                     checkpoint_interval_minutes, ensemble, compare, stability)

namespace fs = std::filesystem;

namespace {
// The layout's version: a reader refuses another (parameters renamed or enumerations reordered).
constexpr int kCaseRecordFormat = 1;
} // namespace

io::Json case_parameters_json(const CaseParameters& p) {
  return p;
}

CaseParameters case_parameters_from_json(const io::Json& j) {
  try {
    return j.get<CaseParameters>();
  } catch (const nlohmann::json::exception& e) {
    throw io::InputError(std::string("case record: ") + e.what());
  }
}

fs::path case_record_file(const fs::path& run_dir) {
  return run_dir / "case.json";
}

void write_case_record(const Case& c, const fs::path& run_dir) {
  io::Json j = {{"format", kCaseRecordFormat}};
  j.update(io::provenance());
  j["case_file"] = c.file;
  j["settings"] = c.settings;
  j["parameters"] = case_parameters_json(c.parameters);
  j["record"] = c.record;
  j["defaults"] = c.defaults;
  io::write_file_atomically(case_record_file(run_dir), io::dump(j));
}

Case read_case_record(const fs::path& run_dir) {
  const fs::path file = case_record_file(run_dir);
  if (!fs::is_directory(run_dir))
    throw io::InputError(run_dir.string() + ": not a run directory (twinflow compare RUNDIR, "
                                            "where RUNDIR is the --out of twinflow run)");
  const io::Json j =
      io::read_json(file, "the case is written by `twinflow run CASE --out " + run_dir.string() +
                              "` before its twins (finished stages are reused)");
  Case c;
  try { // every failure names the file
    if (j.value("format", 0) != kCaseRecordFormat)
      throw io::InputError("format " + j.value("format", io::Json()).dump() +
                           ", this twinflow reads " + std::to_string(kCaseRecordFormat) +
                           " (rerun `twinflow run CASE --out " + run_dir.string() + "`)");
    c.parameters = j.at("parameters").get<CaseParameters>();
    c.record = j.at("record");
    c.defaults = j.value("defaults", io::Json::object());
    c.file = j.value("case_file", std::string());
    c.settings = j.value("settings", std::vector<std::string>());
  } catch (const io::InputError& e) {
    throw io::InputError(file.string() + ": " + e.what());
  } catch (const nlohmann::json::exception& e) {
    throw io::InputError(file.string() + ": " + e.what());
  }
  return c;
}

} // namespace twinflow::study
