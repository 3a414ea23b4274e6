// The twinflow command line: bad input gives exit code 2, names the key, writes nothing.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "run_twinflow.hpp"

namespace fs = std::filesystem;

namespace {

using twinflow::testing::Result;
Result run(const std::string& args) {
  return twinflow::testing::run_twinflow(args);
}

fs::path fresh_dir(const std::string& name) {
  return twinflow::testing::fresh_dir("cli_test", name);
}

// "# expect: token token ..." on the first line of a broken case.
std::string expectation(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  const std::string tag = "# expect: ";
  return line.rfind(tag, 0) == 0 ? line.substr(tag.size()) : "";
}

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().extension() == ".prm") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

} // namespace

// Every shipped case is valid, and none falls where the stability maps saw runs fail (the
// start-up warning stays silent: they run stably).
TEST(Cli, EveryShippedCaseIsValid) {
  const auto cases = files_in(fs::path(TWINFLOW_SOURCE_DIR) / "cases");
  ASSERT_FALSE(cases.empty());
  for (const auto& c : cases) {
    const Result r = run("check-case " + c.string());
    EXPECT_EQ(r.code, 0) << c << "\n" << r.output;
    EXPECT_EQ(r.output.find("warning:"), std::string::npos) << c << "\n" << r.output;
  }
}

// Stiff and biased choices are caught up front: ec-verlet on the 3D cavity at its dt, euler on
// stiff_cavity at dt 0.05 (data/stability_limits.csv), ec-verlet's per-particle offset on the
// column (a pair force between thermal walls), each naming the alternative.
TEST(Cli, StiffChoicesWarnUpFront) {
  const std::string cases = std::string(TWINFLOW_SOURCE_DIR) + "/cases/";
  const std::pair<std::string, std::string> choices[] = {
      {cases + "heated_cavity_3d.prm --set 'Particle/Integrator=ec-verlet'", "stability maps"},
      {cases + "stiff_cavity.prm --set 'Particle/Integrator=euler' --set 'Particle/Time step=0.05'",
       "stability maps"},
      {cases + "conduction_column_repulsive_2d.prm --set 'Particle/Integrator=ec-verlet' --set "
               "'Particle/Time step=0.002'",
       "energy flow in u"}};
  for (const auto& [args, phrase] : choices) {
    const Result r = run("check-case " + args);
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("warning: "), std::string::npos) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(phrase), std::string::npos) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("Particle/Integrator = shardlow"), std::string::npos) << r.output;
  }
}

TEST(Cli, BrokenCasesExitTwoNameTheKeyAndWriteNothing) {
  const auto broken = files_in(fs::path(TWINFLOW_SOURCE_DIR) / "tests" / "broken_cases");
  ASSERT_GE(broken.size(), 10u);
  for (const auto& c : broken) {
    const std::string expect = expectation(c);
    ASSERT_FALSE(expect.empty()) << c << " lacks its '# expect:' line";
    for (const std::string command : {"check-case", "particle", "run"}) {
      const fs::path out = fresh_dir(c.stem().string());
      const Result r = run(command + " " + c.string() + " --out " + out.string());
      EXPECT_EQ(r.code, 2) << command << " " << c << "\n" << r.output;
      // Each expected token appears in the one-line message.
      std::istringstream tokens(expect);
      std::string phrase;
      while (std::getline(tokens, phrase, ' ')) {
        if (phrase.empty()) continue;
        EXPECT_NE(r.output.find(phrase), std::string::npos)
            << command << " " << c << ": missing '" << phrase << "' in\n"
            << r.output;
      }
      EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
      EXPECT_FALSE(fs::exists(out)) << command << " wrote " << out;
    }
  }
}

// A case path that is a directory, an empty file or a binary file: exit 2, one line, nothing
// written (check-case says so too).
TEST(Cli, DirectoryEmptyAndBinaryCasePathsAreRefused) {
  const fs::path dir = fresh_dir("not_cases");
  fs::create_directories(dir / "a_directory");
  std::ofstream(dir / "empty.prm").flush();
  {
    std::ofstream binary(dir / "binary.prm", std::ios::binary);
    binary << std::string("\x7f"
                          "ELF\x02\x01\x01\0\0\0 set x",
                          16)
           << "\n";
  }
  const struct {
    std::string file, expect;
  } cases[] = {{"a_directory", "is a directory, not a case file"},
               {"empty.prm", "is empty"},
               {"binary.prm", "a binary file, not a case file (starts '\\x7FELF\\x02"}};
  for (const auto& c : cases)
    for (const std::string command : {"check-case", "run"}) {
      const fs::path out = dir / "out";
      const Result r = run(command + " " + (dir / c.file).string() + " --out " + out.string());
      EXPECT_EQ(r.code, 2) << command << " " << c.file << "\n" << r.output;
      EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.file << "\n" << r.output;
      EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
      EXPECT_FALSE(fs::exists(out)) << command << " wrote " << out;
    }
}

// Each command's own help (options, an example, exit codes); --version names the libraries.
TEST(Cli, CommandHelpAndVersion) {
  for (const std::string command : {"run", "particle", "transport", "continuum", "compare", "sweep",
                                    "stability", "bench", "check-case", "print-parameters"}) {
    const Result r = run(command + " --help");
    EXPECT_EQ(r.code, 0) << command;
    EXPECT_EQ(r.output.rfind("twinflow " + command, 0), 0u) << r.output;
    EXPECT_NE(r.output.find("example"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("exit codes"), std::string::npos) << r.output;
  }
  const Result help = run("--help");
  EXPECT_NE(help.output.find("6 an output"), std::string::npos) << help.output;
  // The command column is aligned: every description starts in the same column.
  std::istringstream lines(help.output.substr(help.output.find("commands:")));
  std::string line;
  std::getline(lines, line);
  std::size_t column = 0;
  while (std::getline(lines, line) && !line.empty()) {
    const auto gap = line.find("  ", 2);
    ASSERT_NE(gap, std::string::npos) << line;
    const auto start = line.find_first_not_of(' ', gap);
    if (column == 0) column = start;
    EXPECT_EQ(start, column) << line;
  }
  const Result version = run("--version");
  EXPECT_EQ(version.code, 0);
  for (const char* part : {"twinflow ", "(git ", "deal.II 9.", "HDF5 1.", "MPI "})
    EXPECT_NE(version.output.find(part), std::string::npos) << version.output;
}

TEST(Cli, MissingFileUnknownSetKeyAndBadValues) {
  const fs::path out = fresh_dir("misc");
  const std::string good = std::string(TWINFLOW_SOURCE_DIR) + "/cases/equilibrium_ideal_3d.prm";
  struct Case {
    std::string args, expect;
  } cases[] = {
      {"particle /nonexistent/case.prm", "/nonexistent/case.prm: cannot open"},
      {"particle " + good + " --set 'Particle/No such key=1'", "Particle/No such key"},
      {"particle " + good + " --set 'Particle/Time step=0'", "Particle/Time step"},
      {"particle " + good + " --set 'Scene/Density=-3'", "Scene/Density"},
      {"particle " + good + " --threads 0", "--threads"},
      {"frobnicate " + good, "unknown command"},
      // the compressible twin needs c_p > k: checked on the c_p it takes, before writing
      {"continuum " + std::string(TWINFLOW_SOURCE_DIR) +
           "/cases/heated_cavity_2d.prm --set 'Continuum/Coefficients/Heat capacity=1'",
       "Heat capacity"},
  };
  for (const auto& c : cases) {
    const Result r = run(c.args + " --out " + out.string());
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

TEST(Cli, PrintParametersDocumentsEveryKeyAndIsItselfAValidCase) {
  const Result r = run("print-parameters");
  ASSERT_EQ(r.code, 0);
  std::istringstream lines(r.output);
  std::string line, previous, before;
  int sets = 0;
  while (std::getline(lines, line)) {
    if (line.find("set ") != std::string::npos && line.find("# ") == std::string::npos) {
      ++sets;
      EXPECT_NE(previous.find("allowed:"), std::string::npos) << line;
      EXPECT_NE(before.find('#'), std::string::npos) << "no doc string for " << line;
    }
    before = previous;
    previous = line;
  }
  EXPECT_GT(sets, 30);
  const fs::path dir = fresh_dir("defaults");
  fs::create_directories(dir);
  std::ofstream(dir / "defaults.prm") << r.output;
  EXPECT_EQ(run("check-case " + (dir / "defaults.prm").string()).code, 0);
}
