#include "app/commands.hpp"

#include <iostream>

#include "io/files.hpp"
#include "study/bench.hpp"
#include "study/case_file/case_file.hpp"
#include "study/stability_limits.hpp"
#include "study/stages.hpp"
#include "study/sweeps.hpp"

namespace twinflow::app {

using study::CaseFile;

namespace {

study::Case load_case(const CommandLine& cl) {
  CaseFile file;
  return file.load(cl.target, cl.settings);
}

study::GridOptions grid_options(const CommandLine& cl) {
  return {cl.target, cl.settings, cl.vary, cl.rayleigh, cl.run, cl.jobs, cl.launcher, cl.plan};
}

int check_case(const CommandLine& cl) {
  CaseFile file;
  const study::Case c = file.load(cl.target, cl.settings);
  std::cout << "# " << cl.target << ": valid (case '" << c.parameters.name << "', "
            << c.parameters.scene.dim << "D, " << c.parameters.particle.particle_count()
            << " particles)\n";
  for (const auto& warning :
       study::stiff_choice_warnings(c.parameters.particle, study::stability_limits()))
    std::cout << "# " << warning << "\n";
  file.registry().print_resolved(std::cout);
  return 0;
}

int print_parameters(const CommandLine&) {
  CaseFile file;
  std::cout << "# twinflow case-file parameters: every key with its default, allowed values and "
               "documentation.\n# Set them in a .prm file (subsection/set/end; 'include FILE' "
               "reads another file) or with --set 'Section/Key=value'.\n";
  file.registry().print_documented(std::cout);
  return 0;
}

int particle(const CommandLine& cl) {
  return study::particle_command(load_case(cl), cl.run);
}
int transport(const CommandLine& cl) {
  return study::transport_stage(load_case(cl), cl.run);
}
int continuum(const CommandLine& cl) {
  return study::continuum_command(load_case(cl), cl.run);
}
int run(const CommandLine& cl) {
  return study::run_all(load_case(cl), cl.run);
}

// The case the run's twins ran (RUNDIR/case.json), with this command's Compare/ keys over it.
int compare(const CommandLine& cl) {
  return study::compare_stage(study::recorded_case(cl.target, cl.settings), cl.target);
}

int sweep(const CommandLine& cl) {
  return study::sweep(grid_options(cl), study::case_reader(cl.target));
}
int stability(const CommandLine& cl) {
  return study::stability(grid_options(cl), study::case_reader(cl.target));
}
int bench(const CommandLine& cl) {
  particle::ParticleParameters cavity;
  for (const auto& setting : cl.settings)
    if (setting.rfind("Bench/Cavity", 0) == 0) {
      CaseFile file;
      cavity = file.load(study::shipped_case("heated_cavity_2d"), {}).parameters.particle;
    }
  return study::bench(cl.run, cl.settings, cavity);
}

} // namespace

// The options every stage command takes, and the exit codes (docs/usage.md, "Exit codes").
#define TWINFLOW_STAGE_OPTIONS                                                                     \
  "  --out DIR, -o DIR     run directory (default: twinflow-runs/<case name>)\n"                   \
  "  --set 'S/Key=value'   override a case key (repeatable; twinflow print-parameters lists "      \
  "them)\n"                                                                                        \
  "  --seed N              the same as --set Particle/Seed=N\n"                                    \
  "  --ensemble K          the same as --set Particle/Ensemble=K: K realisations, merged\n"        \
  "  --threads N, -t N     OpenMP threads (default: every core; results are the same for any N)\n" \
  "  --force               overwrite an earlier run's results\n"
#define TWINFLOW_RESTART_OPTIONS                                                                   \
  "  --wall-time T         checkpoint and stop after T (3600, 90m, 2h); continue with --restart\n" \
  "  --restart             continue an interrupted particle run from its checkpoint\n"
#define TWINFLOW_EXIT_CODES                                                                        \
  "exit codes: 0 done, 1 internal failure, 2 bad input (nothing written), 4 the particle run\n"    \
  "went unstable, 5 interrupted with a checkpoint (the message prints the command that\n"          \
  "continues), 6 an output could not be written (disk full, permission denied: the message\n"      \
  "names the file and the reason; no incomplete file is left under a final name)\n"

// The options and exit codes of the grid commands (sweep, stability).
#define TWINFLOW_GRID_OPTIONS                                                                      \
  "  --jobs N, -j N        points run at once (default: cores / --threads)\n"                      \
  "  --launcher 'T {cmd}'  each point under a launcher: 'mpirun -np 2 {cmd}', 'srun -n 4 {cmd}'\n" \
  "  --plan                write DIR/points/NNN/command.sh, run nothing (job arrays)\n"            \
  "  --out, --set, --threads, --force as for run\n"
#define TWINFLOW_GRID_EXIT_CODES                                                                   \
  "exit codes: 0 done (however many points failed), 2 bad input (nothing written),\n"              \
  "5 interrupted (the same command continues), 6 an output could not be written\n"

// Each command's `--help` text: usage, what it writes, options, an example, exit codes.
namespace details {
const char* const run =
    "twinflow run CASE [options]\n\n"
    "All stages into RUNDIR: particle/, transport/, continuum/ (nominal twin),\n"
    "continuum_calibrated/ (walled scenes), compare/ and report/report.html. A stage whose\n"
    "inputs are unchanged is reused; changed particle inputs need --force.\n\n"
    "options:\n" TWINFLOW_STAGE_OPTIONS TWINFLOW_RESTART_OPTIONS
    "\nexample (every stage in under a minute):\n"
    "  twinflow run cases/quickstart_2d.prm --out runs/quickstart\n\n" TWINFLOW_EXIT_CODES;
const char* const particle =
    "twinflow particle CASE [options]\n\n"
    "The case's Scene and Particle sections as DPDE particles into RUNDIR/particle/\n"
    "(summary.json, fields.h5 + fields.xdmf, thermo.csv, ...). Checkpoints every\n"
    "Particle/Checkpoint interval minutes (default 10) and when stopped (Ctrl-C, SIGTERM, "
    "SIGUSR1).\n\n"
    "options:\n" TWINFLOW_STAGE_OPTIONS TWINFLOW_RESTART_OPTIONS "\nexample:\n"
    "  twinflow particle cases/heated_cavity_2d.prm --out runs/cavity --set "
    "'Particle/Steps=4000'\n\n" TWINFLOW_EXIT_CODES;
const char* const transport =
    "twinflow transport CASE [options]\n\n"
    "The fluid's coefficients at the case's state point into RUNDIR/transport/: theory, and\n"
    "measured D, p, alpha (kappa and eta with Transport/Measure kappa and eta = true).\n"
    "Measurements are cached in $TWINFLOW_CACHE (default ~/.cache/twinflow; off: none).\n\n"
    "options:\n" TWINFLOW_STAGE_OPTIONS "\nexample:\n"
    "  twinflow transport cases/thermal_relaxation.prm --out "
    "runs/relaxation\n\n" TWINFLOW_EXIT_CODES;
const char* const continuum =
    "twinflow continuum CASE [options]\n\n"
    "The case's continuum twin (Boussinesq, low-Mach or heat conduction) into\n"
    "RUNDIR/continuum/ (summary.json, fields.h5 + fields.xdmf, bins.csv). With\n"
    "Continuum/Coefficients/Source = transport it needs RUNDIR/transport/ first.\n\n"
    "options:\n" TWINFLOW_STAGE_OPTIONS "\nexample:\n"
    "  twinflow continuum cases/continuum_de_vahl_davis_1e4.prm --out "
    "runs/dvd\n\n" TWINFLOW_EXIT_CODES;
const char* const compare =
    "twinflow compare RUNDIR [--set 'Compare/...=value' ...]\n\n"
    "The twins' distances to the particle run of RUNDIR (the --out of twinflow run), with\n"
    "error bars, into RUNDIR/compare/ (metrics.json, bins.csv, ...) and RUNDIR/report/,\n"
    "for the case the twins ran (RUNDIR/case.json).\n\n"
    "options:\n"
    "  --set 'Compare/Key=value'   Compare/ keys over the recorded case\n"
    "\nexample:\n"
    "  twinflow compare runs/quickstart\n\n" TWINFLOW_EXIT_CODES;
const char* const sweep =
    "twinflow sweep CASE --out DIR --vary 'Section/Key=V1,V2,...' [--vary ...] [options]\n\n"
    "`run` at every point of a grid (the Cartesian product of the --vary axes) into\n"
    "DIR/points/NNN/, one table DIR/sweep.csv and a report. The same command again\n"
    "continues an interrupted sweep.\n\n"
    "options:\n"
    "  --vary 'S/Key=V1,V2'  one axis (repeatable; vector components separated by spaces)\n"
    "  --rayleigh R1,R2      target Rayleigh numbers, reached by scaling "
    "|g|\n" TWINFLOW_GRID_OPTIONS "\nexample:\n"
    "  twinflow sweep cases/quickstart_2d.prm --out runs/seeds --vary "
    "'Particle/Seed=1,2,3'\n\n" TWINFLOW_GRID_EXIT_CODES;
const char* const stability =
    "twinflow stability CASE --out DIR --vary 'Section/Key=V1,V2,...' [options]\n\n"
    "`particle` at every point of a grid, each classified (stable, energy_drift,\n"
    "negative_internal_energy, ...) into DIR/stability.csv and a report.\n\n"
    "options:\n"
    "  --vary 'S/Key=V1,V2'  one axis (repeatable)\n" TWINFLOW_GRID_OPTIONS "\nexample:\n"
    "  twinflow stability cases/stiff_cavity.prm --out runs/map --vary 'Particle/Time "
    "step=0.005,0.01'\n\n" TWINFLOW_GRID_EXIT_CODES;
const char* const bench =
    "twinflow bench [--out DIR] [--set 'Bench/Key=value' ...]\n\n"
    "Particle-steps/s per integrator, scene, size and thread count into DIR/bench/\n"
    "(default twinflow-runs/bench). Keys: Bench/N, Bench/N2D, Bench/Scenes,\n"
    "Bench/Integrators, Bench/Threads, Bench/Skin, Bench/Noise, Bench/Steps, Bench/Thermo;\n"
    "Bench/Cavity (particle counts of the default cavity, walled beside its bulk fluid).\n"
    "\nexample:\n"
    "  twinflow bench --set 'Bench/N=6000' --set 'Bench/Threads=1,2'\n"
    "  twinflow bench --set 'Bench/Cavity=1600,6400' --set "
    "'Bench/Threads=1,2'\n\n" TWINFLOW_EXIT_CODES;
const char* const check_case =
    "twinflow check-case CASE [--set 'Section/Key=value' ...]\n\n"
    "Loads the case as every stage would (includes, --set, every value checked) and prints\n"
    "the resolved parameters. Writes nothing.\n"
    "\nexample:\n"
    "  twinflow check-case cases/quickstart_2d.prm --set 'Particle/Steps=2000'\n\n"
    "exit codes: 0 valid, 2 not (one line naming file, line, key and the allowed range)\n";
const char* const print_parameters =
    "twinflow print-parameters\n\n"
    "Every case-file key with its default, allowed values and documentation, as a valid\n"
    "case file (the reference documentation of case files).\n"
    "\nexample:\n"
    "  twinflow print-parameters > all-keys.prm\n\n"
    "exit codes: 0\n";
} // namespace details

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {"run", "CASE", "all stages: particle, transport, continuum twins, compare and report", run,
       details::run},
      {"particle", "CASE", "the DPDE particle scene", particle, details::particle},
      {"transport", "CASE", "the fluid's coefficients: estimated and measured", transport,
       details::transport},
      {"continuum", "CASE", "the deal.II continuum twin", continuum, details::continuum},
      {"compare", "RUNDIR", "compare the twins of a finished run (and write its report)", compare,
       details::compare},
      {"sweep", "CASE", "a grid of paired runs (--vary, --rayleigh)", sweep, details::sweep},
      {"stability", "CASE", "classify particle runs over a parameter grid (--vary)", stability,
       details::stability},
      {"bench", "", "particle-steps/s of the particle core", bench, details::bench},
      {"check-case", "CASE", "validate a case file and print its resolved parameters", check_case,
       details::check_case},
      {"print-parameters", "", "every parameter with its default, range and documentation",
       print_parameters, details::print_parameters},
  };
  return table;
}

} // namespace twinflow::app
