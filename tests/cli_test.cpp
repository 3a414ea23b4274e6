// The twinflow command line: bad input gives exit code 2, names the key, writes nothing.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>

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

TEST(Cli, EveryShippedCaseIsValid) {
  const auto cases = files_in(fs::path(TWINFLOW_SOURCE_DIR) / "cases");
  ASSERT_FALSE(cases.empty());
  for (const auto& c : cases) {
    const Result r = run("check-case " + c.string());
    EXPECT_EQ(r.code, 0) << c << "\n" << r.output;
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
