#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <deal.II/base/mpi.h>

#include "compare/calibration.hpp"
#include "compare/metrics.hpp"
#include "continuum/run.hpp"
#include "continuum/twin_walls.hpp"
#include "io/files.hpp"
#include "study/case_record.hpp"
#include "study/ranks.hpp"
#include "study/stages.hpp"
#include "study/twin_coefficients.hpp"
#include "study/twin_model.hpp"
#include "study/twin_wall_theory.hpp"
#include "transport/coefficients.hpp"

namespace twinflow::study {

namespace fs = std::filesystem;

void take_coefficients(const transport::Coefficients& k, continuum::ContinuumParameters& p) {
  const auto take = [](continuum::PowerLaw& law, const transport::Coefficient& c) {
    law.value_at_reference = c.value;
    if (!std::isfinite(c.exponent)) return;
    law.exponent = c.exponent;
    law.sutherland_temperature = 0; // the measured law replaces any Sutherland law of the case
    law.pair_fraction = c.pair_fraction;
    law.pair_exponent = c.pair_exponent;
  };
  take(p.viscosity, k.viscosity);
  take(p.conductivity, k.conductivity);
  p.heat_capacity = k.heat_capacity_p.value;
  p.thermal_expansion = k.thermal_expansion.value;
  // The fluid's own p(n, T) where the twin has one (the low-Mach twin is ideal-gas only), and
  // the DPD friction's bulk viscosity zeta_D = (1 + 2/d) eta_D (Marsh, Backx & Ernst 1997; the
  // kinetic part has none).
  if (p.model == continuum::Model::Compressible) {
    p.equation_of_state = {k.excess_pressure.b0, k.excess_pressure.b1, k.excess_pressure.b2,
                           k.excess_pressure.n_ref};
    if (std::isfinite(k.viscosity_dissipative))
      p.bulk_viscosity = (1 + 2.0 / p.dim) * k.viscosity_dissipative;
  }
}

namespace {
// The measured coefficients' standard errors (NaN for estimates): the twin's own uncertainty.
struct CoefficientErrors {
  double conductivity = std::nan(""), viscosity = std::nan("");
  // their laws' powers of T (the fits' errors; a measured law's shape is uncertain too)
  double conductivity_exponent = std::nan(""), viscosity_exponent = std::nan("");
};

// What the twin took from the transport stage.
struct TakenCoefficients {
  transport::Coefficients coefficients;
  CoefficientErrors errors;
};

// The transport stage's coefficients at the twin's reference temperature (one reader:
// transport/coefficients.hpp), with the errors of the measured ones.
TakenCoefficients take_transport_coefficients(const fs::path& run_dir, const CaseParameters& c,
                                              continuum::ContinuumParameters& p) {
  const std::string& source = c.transport.source;
  const fs::path file = run_dir / "transport" / "summary.json";
  const io::Json summary =
      io::read_json(file, "Continuum/Coefficients/Source = transport needs `twinflow transport "
                          "CASE --out " +
                              run_dir.string() + "` first");
  const transport::Coefficients k =
      transport::read_coefficients(summary, source, p.reference_temperature);
  const auto say = [&](const char* what, const transport::Coefficient& c) {
    std::cout << "continuum: " << what << " = " << c.value << " ("
              << (c.measured ? "measured" : "estimated") << ", from " << file.string() << ")\n";
  };
  take_coefficients(k, p);
  const auto say_law = [&](const char* what, const continuum::PowerLaw& law,
                           const transport::Coefficient& c) {
    say(what, c);
    if (!std::isfinite(c.exponent)) return;
    std::cout << "continuum: " << what << "(T) = " << law.value_at_reference << " (T / "
              << p.reference_temperature << ")^" << c.exponent
              << " (measured at T = " << k.measured_temperature << ")\n";
  };
  say_law("eta", p.viscosity, k.viscosity);
  say_law("kappa", p.conductivity, k.conductivity);
  say("c_p", k.heat_capacity_p);
  say("alpha", k.thermal_expansion);
  if (p.model == continuum::Model::Compressible) { // what take_coefficients gave it besides
    const transport::ExcessPressure& e = k.excess_pressure;
    if (std::isfinite(k.viscosity_dissipative))
      std::cout << "continuum: bulk viscosity zeta = (1 + 2/d) eta_D = " << p.bulk_viscosity
                << " (estimated: eta's dissipative part " << k.viscosity_dissipative << ", from "
                << file.string() << ")\n";
    if (e.fitted)
      std::cout << "continuum: p = n T + n^2 (b0 + b1 T + b2 (n - " << e.n_ref
                << ")), b0 = " << e.b0 << " +- " << e.b0_stderr << ", b1 = " << e.b1 << " +- "
                << e.b1_stderr << ", b2 = " << e.b2 << " +- " << e.b2_stderr
                << " (fitted to the bulk runs, from " << file.string() << ")\n";
    if (!e.found)
      std::cout << "continuum: " << file.string()
                << " has no equation of state (an older measurement): the twin takes the ideal "
                   "fluid's\n";
  }
  if (c.twin.wall_jumps_from_theory) take_wall_jumps(c, k, p);
  if (c.twin.wall_slips_from_theory) take_wall_slips(c, p);
  return {k,
          {k.conductivity.stderr_, k.viscosity.stderr_, k.conductivity.exponent_stderr,
           k.viscosity.exponent_stderr}};
}

// The wall theory's fluid density is the twin's own at each wall (its pressure, its
// stratification, its equation of state), not the isobar's first guess: fixed-point passes, a
// solve each (no files; one mesh level less: a wall's mean density is a smooth field), until no
// conductance moves by 2%.
void take_wall_densities_from_twin(const CaseParameters& c, const transport::Coefficients& k,
                                   continuum::ContinuumParameters& p, MPI_Comm comm) {
  for (int pass = 1; pass <= 4; ++pass) {
    continuum::ContinuumParameters coarser = p;
    coarser.refinements = std::max(0, p.refinements - 1);
    const continuum::ContinuumResult r = continuum::run(coarser, "", comm);
    const WallValues n = wall_densities(r.bins, p.dim);
    std::cout << "continuum: the wall model at the twin's own densities, pass " << pass << "\n";
    continuum::ContinuumParameters next = p;
    const WallValues T = wall_values(r.bins, p.dim, "T");
    if (c.twin.wall_slips_from_theory) take_wall_slips(c, next, &n, &T);
    if (take_wall_jumps(c, k, next, &n) == 0) return;
    double change = 0;
    for (int d = 0; d < p.dim; ++d)
      for (int side = 0; side < 2; ++side) {
        const double was = p.boundary[d].kapitza_conductance[side];
        const double now = next.boundary[d].kapitza_conductance[side];
        if (was != now) change = std::max(change, std::fabs(now / was - 1));
        const double was_depth = p.boundary[d].pinned_depth[side];
        const double depth = next.boundary[d].pinned_depth[side];
        if (was_depth != depth) change = std::max(change, std::fabs(depth / was_depth - 1));
      }
    p = next;
    if (change < 0.02) return;
  }
}

// The twin's heat flux and bins as its coefficients, and its Kapitza conductances, move by their
// standard errors, one at a time (one more solve each, no files): the part of a particle-twin
// difference the twin's own inputs can explain.
struct Uncertainty {
  io::Json json;
  std::vector<continuum::BinResponse> responses; // each input's +1 stderr change of the bins
};

continuum::BinAverages bins_change(const continuum::BinAverages& moved,
                                   const continuum::BinAverages& base) {
  continuum::BinAverages d = moved;
  d.domain_values.clear(); // the change of the scene's bins only
  for (std::size_t c = 0; c < d.values.size(); ++c)
    for (std::size_t k = 0; k < d.values[c].size(); ++k) d.values[c][k] -= base.values[c][k];
  return d;
}

Uncertainty coefficient_uncertainty(const continuum::ContinuumParameters& p,
                                    const CoefficientErrors& errors,
                                    const continuum::ContinuumResult& base, MPI_Comm comm) {
  Uncertainty u;
  io::Json& j = u.json = io::Json::object();
  const double heat_flux = base.nusselt * base.numbers.conduction_flux;
  double variance = 0;
  const auto vary = [&](const std::string& name, double stderr_, auto shift) {
    if (!std::isfinite(stderr_) || stderr_ <= 0) return;
    continuum::ContinuumParameters shifted = p;
    const double value = shift(shifted, stderr_);
    double change = std::nan("");
    try {
      const continuum::ContinuumResult r = continuum::run(shifted, "", comm);
      change = r.nusselt * r.numbers.conduction_flux / heat_flux - 1;
      if (r.bins.names == base.bins.names && r.bins.bins == base.bins.bins)
        u.responses.push_back({name, bins_change(r.bins, base.bins)});
    } catch (const std::exception& e) { // the twin itself converged: keep it, say what failed
      std::cout << "continuum: the solve with " << name << " + 1 stderr failed (" << e.what()
                << ")\n";
    }
    io::Json c = io::Json::object();
    c["value"] = value;
    c["stderr"] = stderr_;
    c["heat_flux_relative_change"] = change; // linear response to +1 stderr
    j[name] = c;
    variance += change * change;
  };
  const auto law = [](auto member) {
    return [member](continuum::ContinuumParameters& q, double by) {
      (q.*member).value_at_reference += by;
      return (q.*member).value_at_reference - by;
    };
  };
  vary("conductivity", errors.conductivity, law(&continuum::ContinuumParameters::conductivity));
  vary("viscosity", errors.viscosity, law(&continuum::ContinuumParameters::viscosity));
  // A law's power of T, its value at the reference temperature held (where the law has one).
  const auto power = [](auto member) {
    return [member](continuum::ContinuumParameters& q, double by) {
      (q.*member).exponent += by;
      return (q.*member).exponent - by;
    };
  };
  if (p.conductivity.exponent != 0)
    vary("conductivity_exponent", errors.conductivity_exponent,
         power(&continuum::ContinuumParameters::conductivity));
  if (p.viscosity.exponent != 0)
    vary("viscosity_exponent", errors.viscosity_exponent,
         power(&continuum::ContinuumParameters::viscosity));
  for (int d = 0; d < p.dim; ++d)
    for (int side = 0; side < 2; ++side)
      vary("kapitza_" + scene::wall_name(d, side), p.boundary[d].kapitza_conductance_stderr[side],
           [d, side](continuum::ContinuumParameters& q, double by) {
             q.boundary[d].kapitza_conductance[side] += by;
             return q.boundary[d].kapitza_conductance[side] - by;
           });
  j["heat_flux_relative_stderr"] = std::sqrt(variance); // the errors taken as independent
  return u;
}

bool has_kapitza_errors(const continuum::ContinuumParameters& p) {
  for (const auto& b : p.boundary)
    for (const double e : b.kapitza_conductance_stderr)
      if (e > 0) return true;
  return false;
}

const char* model_name(continuum::Model m) {
  return m == continuum::Model::Boussinesq     ? "Boussinesq"
         : m == continuum::Model::LowMach      ? "low-Mach"
         : m == continuum::Model::Compressible ? "compressible"
                                               : "heat conduction";
}
} // namespace

namespace {
// The twin's model, its numbers and a note where its equation of state leaves the fluid's
// conservative force out.
void announce_twin(const CaseParameters& parameters, const continuum::ContinuumParameters& p) {
  const auto numbers = continuum::dimensionless_numbers(p);
  if (parameters.twin.model_chosen_automatically && parameters.scene.has_walls())
    std::cout << "continuum: Model = auto: " << model_name(p.model) << " ("
              << automatic_model_reason(parameters.scene, p.particle_mass, p.model,
                                        parameters.twin.low_mach_threshold,
                                        parameters.twin.compressible_threshold)
              << ")\n";
  std::cout << "continuum: " << model_name(p.model) << (p.transient() ? " in time" : ", steady")
            << ", " << p.dim << "D, Ra = " << numbers.rayleigh << ", Pr = " << numbers.prandtl
            << ", epsilon = " << numbers.epsilon
            << ", g H / c^2 = " << parameters.scene.stratification(p.particle_mass) << std::endl;
  const bool eos_matters =
      p.model == continuum::Model::LowMach || p.model == continuum::Model::Compressible;
  if (eos_matters && parameters.particle.conservative != particle::ConservativeForce::None &&
      p.equation_of_state.ideal())
    std::cout << "continuum: note: the twin's equation of state is the ideal DPDE fluid's, "
                 "p = n k T; this fluid's conservative force adds to its pressure, which the "
              << (p.model == continuum::Model::LowMach
                      ? "low-Mach twin leaves out (the compressible twin takes the transport "
                        "stage's fit)\n"
                      : "twin leaves out (Coefficients/Excess pressure, or Source = transport)\n");
}

// bins.csv and, where the twin has them, wall_nusselt.csv and time_series.csv; returns every
// file the stage wrote.
std::vector<std::string> write_twin_tables(const io::StageDirectory& stage,
                                           const continuum::ContinuumResult& result,
                                           const continuum::ContinuumParameters& p) {
  io::write_file_atomically(stage.file("bins.csv"), continuum::bins_csv(result, p));
  std::vector<std::string> files = result.files;
  files.push_back("bins.csv");
  if (!result.walls.empty() && !result.walls.front().local.empty()) {
    io::write_file_atomically(stage.file("wall_nusselt.csv"), continuum::wall_nusselt_csv(result));
    files.push_back("wall_nusselt.csv");
  }
  if (!result.time_series.empty()) {
    io::write_file_atomically(stage.file("time_series.csv"), continuum::time_series_csv(result));
    files.push_back("time_series.csv");
  }
  return files;
}

void print_twin_result(const continuum::ContinuumResult& result,
                       const continuum::ContinuumParameters& p, const io::StageDirectory& stage,
                       const std::vector<std::string>& files) {
  if (result.model == "boussinesq" || result.model == "low-mach") {
    std::cout << "continuum: ";
    if (p.transient()) std::cout << "at t = " << result.time << ", ";
    std::cout << "Nu = " << result.nusselt;
    if (result.model == "low-mach") std::cout << ", P/p0 = " << result.pressure_ratio;
    if (result.has_midline_maxima)
      std::cout << ", u_max(x = Lx/2) = " << result.u_max_vertical_midline.value
                << ", v_max(y = Ly/2) = " << result.v_max_horizontal_midline.value << " (chi/H)";
    std::cout << "\n";
  }
  std::cout << "continuum: results in " << stage.path().string() << " (summary.json";
  for (const auto& f : files) std::cout << ", " << f;
  std::cout << ")" << std::endl;
}
// summary.json's "coefficient_uncertainty" and coefficient_responses.csv (compare's twin error
// per bin) where the twin's inputs carry errors (a steady flow on one process: the extra solves
// run there).
void add_coefficient_uncertainty(const continuum::ContinuumParameters& p,
                                 const continuum::ContinuumResult& result,
                                 const CoefficientErrors& coefficient_errors, unsigned n_processes,
                                 MPI_Comm comm, const io::StageDirectory& stage, io::Json& summary,
                                 std::vector<std::string>& files) {
  const bool has_errors = std::isfinite(coefficient_errors.conductivity) ||
                          std::isfinite(coefficient_errors.viscosity) || has_kapitza_errors(p);
  if (has_errors && n_processes > 1)
    std::cout << "continuum: the coefficients' effect on the heat flux is not computed under "
                 "mpirun (its extra solves run on one process)\n";
  if (result.model == "heat-conduction" || p.transient() || n_processes > 1 || !has_errors) return;
  const Uncertainty u = coefficient_uncertainty(p, coefficient_errors, result, comm);
  summary["coefficient_uncertainty"] = u.json;
  if (!u.responses.empty()) {
    io::write_file_atomically(stage.file("coefficient_responses.csv"),
                              continuum::bin_responses_csv(u.responses, p, result.dim));
    files.push_back("coefficient_responses.csv");
  }
  std::cout << "continuum: heat flux +- "
            << 100 * io::number(summary, {"coefficient_uncertainty", "heat_flux_relative_stderr"})
            << "% from the measured coefficients' errors"
            << (has_kapitza_errors(p) ? " and the Kapitza conductances'" : "") << "\n";
}
} // namespace

int continuum_stage(const Case& c, const RunOptions& options, const std::string& stage_name) {
  const auto start = std::chrono::steady_clock::now();
  const CaseParameters& parameters = c.parameters;
  const fs::path run_dir = run_directory(options, parameters.name);
  continuum::ContinuumParameters p = parameters.continuum;
  TakenCoefficients taken;
  if (parameters.twin.coefficients_from_transport)
    taken = take_transport_coefficients(run_dir, parameters, p);
  const CoefficientErrors& coefficient_errors = taken.errors;
  // Under mpirun only the distributed (iterative) path shares the work; rank 0 writes the
  // summary and tables, the HDF5 fields are written collectively. Inside `run` under mpirun the
  // twin runs on rank 0 alone (the other ranks only took part in the particle runs).
  const MPI_Comm comm = rank_zero_alone() ? MPI_COMM_SELF : MPI_COMM_WORLD;
  const unsigned n_processes = dealii::Utilities::MPI::n_mpi_processes(comm);
  const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  if (n_processes > 1 && !p.uses_iterative_solver())
    throw io::InputError("'continuum' with " + std::to_string(n_processes) +
                         " MPI processes: only the iterative 3D Boussinesq path runs in parallel "
                         "(Continuum/Solver/Linear solver = iterative); run it on one process");
  // Checked on the c_p the twin takes (the case's, or with `run` the transport stage's), before
  // anything is written.
  if (p.model == continuum::Model::Compressible && !(p.heat_capacity > 1))
    throw io::InputError(
        "'Continuum/Coefficients/Heat capacity' = " + std::to_string(p.heat_capacity) +
        " for the compressible twin" +
        (parameters.twin.model_chosen_automatically ? " (Model = auto chose it)" : "") +
        "; allowed: > 1 (c_p > k: c_V = c_p - k > 0), or Coefficients/Source = transport");
  const io::StageDirectory stage(run_dir, stage_name, options.force);
  if (root) announce_twin(parameters, p);
  if (root) stage.create();
  MPI_Barrier(comm);
  if (parameters.twin.coefficients_from_transport && parameters.twin.wall_jumps_from_theory)
    take_wall_densities_from_twin(parameters, taken.coefficients, p, comm);
  const continuum::ContinuumResult result = continuum::run(p, stage.path(), comm);
  if (!root) return 0;
  std::vector<std::string> files = write_twin_tables(stage, result, p);
  io::Json summary = io::Json::object();
  summary["stage"] = "continuum";
  summary["case"] = parameters.name;
  summary["case_file"] = c.file;
  summary["provenance"] = io::provenance();
  summary["execution"] = execution_record(p.dim);
  summary["execution"]["continuum_processes"] = n_processes;
  summary["case_parameters"] = c.record;
  summary["continuum_parameters"] = continuum::to_json(p);
  const io::Json measured = continuum::to_json(result);
  for (const auto& [key, value] : measured.items()) summary[key] = value;
  add_coefficient_uncertainty(p, result, coefficient_errors, n_processes, comm, stage, summary,
                              files);
  summary["files"] = io::Json::array();
  for (const auto& f : files) summary["files"].push_back(f);
  summary["stage_wall_time_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  io::write_file_atomically(stage.file("summary.json"), io::dump(summary));
  print_twin_result(result, p, stage, files);
  return 0;
}

int continuum_command(const Case& c, const RunOptions& options) {
  const int rc = continuum_stage(c, options);
  if (rc == 0 && on_rank_zero()) write_case_record(c, run_directory(options, c.parameters.name));
  return rc;
}

} // namespace twinflow::study
