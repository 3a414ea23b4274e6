// twinflow: run a thermal flow as DPDE particles and as a continuum, and compare the twins.

#include <boost/program_options.hpp>

#include <deal.II/base/config.h>
#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>

#include <omp.h>
#include <unistd.h>

#include "app/commands.hpp"
#include "io/files.hpp"
#include "io/isa.hpp"
#include "study/case.hpp"
#include "study/grid.hpp"
#include "study/ranks.hpp"

namespace po = boost::program_options;
using namespace twinflow;

namespace {

const app::Command* find_command(const std::string& name) {
  for (const auto& c : app::commands())
    if (name == c.name) return &c;
  return nullptr;
}

void usage(std::ostream& out, const po::options_description& opts) {
  out << "usage: twinflow COMMAND [CASE|RUNDIR] [options]\n"
         "       twinflow COMMAND --help      (that command's options, an example, exit codes)\n"
         "       twinflow --version\n\ncommands:\n";
  std::size_t width = 0;
  for (const auto& c : app::commands())
    width = std::max(width, std::string(c.name).size() + 1 + std::string(c.arguments).size());
  for (const auto& c : app::commands()) {
    std::string head = std::string(c.name) + (*c.arguments ? " " : "") + c.arguments;
    head.resize(width + 2, ' ');
    out << "  " << head << c.help << "\n";
  }
  out << "\n"
      << opts
      << "\nexit codes: 0 done, 1 internal failure, 2 bad input (nothing written), 4 the particle\n"
         "run went unstable, 5 interrupted with a checkpoint (--restart continues), 6 an output\n"
         "could not be written (disk full, permission denied; the message names file and reason)\n"
         "\nfirst run: twinflow run cases/quickstart_2d.prm (every stage in under a minute)\n";
}

void version(std::ostream& out) {
  int major = 0, minor = 0, length = 0;
  MPI_Get_version(&major, &minor);
  char library[MPI_MAX_LIBRARY_VERSION_STRING] = {};
  MPI_Get_library_version(library, &length);
  std::string mpi_library(library, static_cast<std::size_t>(std::max(length, 0)));
  mpi_library = mpi_library.substr(0, mpi_library.find_first_of(",\n"));
  out << io::version_line() << "\n"
      << "deal.II " << DEAL_II_PACKAGE_VERSION << ", " << io::hdf5_version() << ", MPI " << major
      << "." << minor << " (" << mpi_library << ")\n"
      << "particle kernels: " << io::isa_name(io::kernel_isa()) << " (this build on this host runs";
  for (const io::Isa isa : io::runnable_isas()) out << " " << io::isa_key(isa);
  out << "; TWINFLOW_ISA chooses)\n" << io::host_line() << "\n";
}

// The command line as typed, every option kept, with --restart: what continues an interrupted
// run (the same case, --set, --threads, --seed, --out; --restart once).
std::string continue_command(int argc, char** argv) {
  std::string out = study::shell_quoted(argv[0]);
  bool restart = false;
  for (int i = 1; i < argc; ++i) {
    restart |= std::string(argv[i]) == "--restart";
    out += " " + study::shell_quoted(argv[i]);
  }
  return restart ? out : out + " --restart";
}

// "3600", "90m", "2h", "30s" -> seconds
double parse_duration(const std::string& text) {
  std::size_t used = 0;
  double value = -1;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
  }
  const std::string unit = text.substr(std::min(used, text.size()));
  const double scale = unit.empty() || unit == "s" ? 1 : unit == "m" ? 60 : unit == "h" ? 3600 : -1;
  if (!(value > 0) || scale < 0)
    throw io::InputError("--wall-time '" + text +
                         "': allowed: a positive number of seconds, or "
                         "with a unit s, m or h (e.g. 90m)");
  return value * scale;
}

// "1e3, 1e4,3e4" -> numbers > 0
std::vector<double> parse_rayleigh_list(const std::string& text) {
  std::vector<double> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    std::size_t used = 0;
    double value = -1;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
    }
    if (!(value > 0) || !std::isfinite(value) ||
        item.find_first_not_of(" \t", used) != std::string::npos)
      throw io::InputError("--rayleigh '" + text +
                           "': allowed: numbers > 0 separated by commas (e.g. 1e3,1e4)");
    values.push_back(value);
    start = comma + 1;
  }
  return values;
}

// Between parallel regions OpenMP's idle threads wait. libgomp's default spins 300000 times
// (~6 ms) before it sleeps: fastest on an idle machine, but on a shared one a spinning thread
// holds the core its partner needs (N = 6000, 2 threads, beside four busy processes: 0.3-1.8e6
// particle-steps/s against 2.1-3.7e6 with OMP_WAIT_POLICY=passive). A spin of 1000 (~25 us)
// keeps both on the Zen 5 host. Where a wake-up is slow (65-120 us on a Zen 3 VM) 3000 ran the
// idle default cavity 15% faster but a run beside one other 2-thread job 20% slower
// (docs/performance.md, "How idle threads wait"): 1000 stays. libgomp reads its environment
// when it is loaded, before main, so the default is set by running again with it; a user's
// OMP_WAIT_POLICY or GOMP_SPINCOUNT is left alone.
void default_openmp_wait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  setenv("GOMP_SPINCOUNT", "1000", 1);
  execv("/proc/self/exe", argv); // returns only on failure: go on with the runtime's default
}

// Every option the command line takes (the help shows them).
po::options_description visible_options() {
  po::options_description opts("options");
  opts.add_options()("help,h", "this help")("out,o", po::value<std::string>(),
                                            "run directory (default: twinflow-runs/<case name>)")(
      "set,s", po::value<std::vector<std::string>>()->composing(),
      "override a case parameter: --set 'Particle/Time step=0.01' (repeatable)")(
      "version", "version, git revision, deal.II, HDF5 and MPI versions")(
      "threads,t", po::value<int>(), "OpenMP threads")("seed", po::value<long>(),
                                                       "random seed (Particle/Seed)")(
      "ensemble", po::value<long>(),
      "independent realisations of the particle run, merged (Particle/Ensemble)")(
      "force", "overwrite an earlier run's results")(
      "restart", "continue an interrupted run from its checkpoint")(
      "wall-time", po::value<std::string>(),
      "checkpoint and stop after this long (e.g. 3600, 90m, 2h); continue with --restart")(
      "vary", po::value<std::vector<std::string>>()->composing(),
      "sweep, stability: one axis of the grid, 'Section/Key=V1,V2,...' (repeatable; vector "
      "components separated by spaces: 'Scene/Gravity=0 -0.01,0 -0.02')")(
      "rayleigh", po::value<std::string>(),
      "sweep: target Rayleigh numbers R1,R2,... reached by scaling |g|")(
      "jobs,j", po::value<int>(),
      "sweep, stability: points run at once (default: cores / threads per point; 1 with "
      "--launcher)")("launcher", po::value<std::string>(),
                     "sweep, stability: run each point under this command, {cmd} the point's "
                     "command: 'mpirun -np 2 {cmd}', 'srun -n 4 {cmd}'")(
      "plan", "sweep, stability: write each point's command as DIR/points/NNN/command.sh (for a "
              "job array) and run nothing");
  return opts;
}

// The options every command shares: --out, --set, --seed, --ensemble, --threads, --force,
// --restart,
// --wall-time.
void read_run_options(const po::variables_map& vm, int argc, char** argv, app::CommandLine& cl) {
  if (vm.count("out")) cl.run.out = vm["out"].as<std::string>();
  if (vm.count("set")) cl.settings = vm["set"].as<std::vector<std::string>>();
  if (vm.count("seed"))
    cl.settings.push_back("Particle/Seed=" + std::to_string(vm["seed"].as<long>()));
  if (vm.count("ensemble"))
    cl.settings.push_back("Particle/Ensemble=" + std::to_string(vm["ensemble"].as<long>()));
  if (vm.count("threads")) {
    cl.run.threads = vm["threads"].as<int>();
    if (cl.run.threads < 1)
      throw io::InputError("--threads " + std::to_string(cl.run.threads) + ": allowed: >= 1");
    omp_set_num_threads(cl.run.threads);
  }
  cl.run.force = vm.count("force") > 0;
  cl.run.continue_command = continue_command(argc, argv);
  cl.run.restart = vm.count("restart") > 0;
  if (vm.count("wall-time"))
    cl.run.wall_time_limit = parse_duration(vm["wall-time"].as<std::string>());
}

// The grid's options (sweep, stability), refused for the other commands.
void read_grid_options(const po::variables_map& vm, app::CommandLine& cl) {
  const bool grid_command = cl.command == "sweep" || cl.command == "stability";
  for (const char* option : {"vary", "rayleigh", "jobs", "launcher", "plan"})
    if (vm.count(option) && !grid_command)
      throw io::InputError(std::string("--") + option + " belongs to sweep and stability, not '" +
                           cl.command + "'");
  if (vm.count("rayleigh") && cl.command != "sweep")
    throw io::InputError("--rayleigh belongs to sweep, not '" + cl.command + "'");
  if (vm.count("wall-time") && grid_command)
    throw io::InputError("--wall-time is not available for " + cl.command +
                         " (stop it with Ctrl-C; running the same command again continues it)");
  if (vm.count("vary")) cl.vary = vm["vary"].as<std::vector<std::string>>();
  if (vm.count("rayleigh")) cl.rayleigh = parse_rayleigh_list(vm["rayleigh"].as<std::string>());
  if (vm.count("launcher")) {
    cl.launcher = vm["launcher"].as<std::string>();
    study::check_launcher(cl.launcher);
  }
  cl.plan = vm.count("plan") > 0;
  if (vm.count("jobs")) {
    cl.jobs = vm["jobs"].as<int>();
    if (cl.jobs < 1) throw io::InputError("--jobs " + std::to_string(cl.jobs) + ": allowed: >= 1");
  }
}

// Parses the command line and runs its command; --help and --version answer here.
int run_command_line(int argc, char** argv) {
  const po::options_description opts = visible_options();
  po::options_description hidden;
  hidden.add_options()("command", po::value<std::string>())("target", po::value<std::string>());
  po::positional_options_description positional;
  positional.add("command", 1).add("target", 1);
  po::options_description all;
  all.add(opts).add(hidden);
  po::variables_map vm;
  po::store(po::command_line_parser(argc, argv).options(all).positional(positional).run(), vm);
  po::notify(vm);
  if (vm.count("version")) {
    version(std::cout);
    return 0;
  }
  const app::Command* command =
      vm.count("command") ? find_command(vm["command"].as<std::string>()) : nullptr;
  if (vm.count("help") && command) {
    std::cout << command->details;
    return 0;
  }
  if (vm.count("help") || !vm.count("command")) {
    usage(vm.count("help") ? std::cout : std::cerr, opts);
    return vm.count("help") ? 0 : 2;
  }
  app::CommandLine cl;
  cl.command = vm["command"].as<std::string>();
  if (!command)
    throw io::InputError("unknown command '" + cl.command + "' (twinflow --help lists them)");
  if (vm.count("target")) cl.target = vm["target"].as<std::string>();
  if (*command->arguments && cl.target.empty())
    throw io::InputError("'" + cl.command + "' needs a CASE file (or RUNDIR)");
  read_run_options(vm, argc, argv, cl);
  read_grid_options(vm, cl);
  io::kernel_isa(); // a TWINFLOW_ISA this host cannot run stops here, before anything is written
  if (study::rank_count() > 1 && study::on_rank_zero()) // how this run is spread, first
    std::cout << "twinflow: " << study::ranks_and_threads() << std::endl;
  return command->run(cl);
}

} // namespace

int main(int argc, char** argv) {
  default_openmp_wait(argv);
  study::save_environment_before_mpi(); // what sweep --launcher hands an MPI launcher
  // One process; deal.II's solvers and HDF5 expect MPI initialised.
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // Under mpirun rank 0 prints; the other ranks' console lines would repeat its own (their
  // errors still reach stderr).
  if (!study::on_rank_zero() && !std::freopen("/dev/null", "w", stdout))
    std::cout.setstate(std::ios::badbit);
  // Line by line into a log file too (`twinflow run ... > log`), so that the log shows a long
  // run's stages as they happen rather than at exit.
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
  // The exit codes: docs/usage.md, "Exit codes".
  try {
    return run_command_line(argc, argv);
  } catch (const po::error& e) {
    std::cerr << "twinflow: error: " << e.what() << " (twinflow --help)\n";
    return 2;
  } catch (const io::InputError& e) {
    std::cerr << "twinflow: error: " << e.what() << "\n";
    return 2;
  } catch (const io::OutputError& e) {
    std::cerr << "twinflow: output failed: " << e.what() << "\n";
    return study::kExitOutputFailed;
  } catch (const std::filesystem::filesystem_error& e) {
    std::cerr << "twinflow: output failed: " << e.what() << "\n";
    return study::kExitOutputFailed;
  } catch (const std::exception& e) {
    std::cerr << "twinflow: failed: " << e.what() << "\n";
    return 1;
  }
}
