#include "app/commands.hpp"

#include <filesystem>
#include <iostream>

#include "app/case/case.hpp"
#include "io/files.hpp"
#include "study/bench.hpp"
#include "study/stages.hpp"
#include "study/sweeps.hpp"

namespace twinflow::app {

namespace fs = std::filesystem;

namespace {

study::Case load_case(const CommandLine& cl) {
  CaseFile file;
  return file.load(cl.target, cl.settings);
}

study::GridOptions grid_options(const CommandLine& cl) {
  return {cl.target, cl.settings, cl.vary, cl.rayleigh, cl.run, cl.jobs};
}

// The case file for a grid's points: read, resolved, or only its record.
study::CaseReader case_reader(const std::string& file) {
  study::CaseReader r;
  r.check = [file](const std::vector<std::string>& settings) { CaseFile().read(file, settings); };
  r.load = [file](const std::vector<std::string>& settings) {
    return CaseFile().load(file, settings);
  };
  r.record = [file](const std::vector<std::string>& settings) {
    CaseFile c;
    c.read(file, settings);
    return c.registry().resolved_json();
  };
  return r;
}

int check_case(const CommandLine& cl) {
  CaseFile file;
  const study::Case c = file.load(cl.target, cl.settings);
  std::cout << "# " << cl.target << ": valid (case '" << c.parameters.name << "', "
            << c.parameters.scene.dim << "D, " << c.parameters.particle.particle_count()
            << " particles)\n";
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
  return study::continuum_stage(load_case(cl), cl.run);
}
int run(const CommandLine& cl) {
  return study::run_all(load_case(cl), cl.run);
}

// The case as the particle run recorded it, with this command's later sections over it.
int compare(const CommandLine& cl) {
  const fs::path run_dir = cl.target;
  if (!fs::is_directory(run_dir))
    throw io::InputError(run_dir.string() + ": not a run directory (twinflow compare RUNDIR, "
                                            "where RUNDIR is the --out of twinflow run)");
  const io::Json summary =
      io::read_json(run_dir / "particle" / "summary.json",
                    "the particle stage has not finished in " + run_dir.string() +
                        " (twinflow run CASE --out " + run_dir.string() + ")");
  CaseFile file;
  const study::Case c =
      file.load_recorded(summary.at("parameters"), io::text(summary, {"case"}), cl.settings);
  return study::compare_stage(c, run_dir);
}

int sweep(const CommandLine& cl) {
  return study::sweep(grid_options(cl), case_reader(cl.target));
}
int stability(const CommandLine& cl) {
  return study::stability(grid_options(cl), case_reader(cl.target));
}
int bench(const CommandLine& cl) {
  return study::bench(cl.run, cl.settings);
}

} // namespace

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {"run", "CASE", "all stages: particle, transport, continuum twins, compare and report", run},
      {"particle", "CASE", "the DPDE particle scene", particle},
      {"transport", "CASE", "the fluid's coefficients: estimated and measured", transport},
      {"continuum", "CASE", "the deal.II continuum twin", continuum},
      {"compare", "RUNDIR", "compare the twins of a finished run (and write its report)", compare},
      {"sweep", "CASE", "a grid of paired runs (--vary, --rayleigh)", sweep},
      {"stability", "CASE", "classify particle runs over a parameter grid (--vary)", stability},
      {"bench", "", "particle-steps/s of the particle core", bench},
      {"check-case", "CASE", "validate a case file and print its resolved parameters", check_case},
      {"print-parameters", "", "every parameter with its default, range and documentation",
       print_parameters},
  };
  return table;
}

} // namespace twinflow::app
