// The particle kernels' instruction-set levels (io/isa.hpp): every level this host runs gives the
// same bytes, --version names the level in use, and a level the host cannot run is refused.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "io/files.hpp"
#include "run_twinflow.hpp"

namespace fs = std::filesystem;
using twinflow::testing::Result;
using twinflow::testing::run_twinflow;

namespace {
const std::vector<std::string> kLevels{"baseline", "avx2", "avx512"};

bool host_runs(const std::string& level) {
  return run_twinflow("--version", "off", "TWINFLOW_ISA=" + level).code == 0;
}

// thermo.csv and fields.csv of one short run on each level the host runs, against the baseline's.
void expect_same_bytes_on_every_level(const std::string& name, const std::string& args) {
  if (!host_runs("baseline")) GTEST_SKIP() << "a TWINFLOW_NATIVE build carries one level";
  std::string reference[2];
  for (const std::string& level : kLevels) {
    if (!host_runs(level)) {
      std::cout << name << ": this host does not run " << level << ", skipped\n";
      continue;
    }
    const fs::path dir = twinflow::testing::fresh_dir("isa_test", name + "_" + level);
    const Result r = run_twinflow("particle " + args + " --threads 2 --out " + dir.string(), "off",
                                  "TWINFLOW_ISA=" + level);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string files[2] = {twinflow::io::read_file(dir / "particle" / "thermo.csv"),
                                  twinflow::io::read_file(dir / "particle" / "fields.csv")};
    for (int f = 0; f < 2; ++f) {
      if (level == kLevels.front()) reference[f] = files[f];
      EXPECT_TRUE(files[f] == reference[f]) << name << ": " << level << " differs from baseline";
    }
    std::cout << name << ": " << level << " ran\n";
  }
}
} // namespace

// The default cavity (2D, walls, shardlow), a 3D fluid with a conservative force (shardlow) and one
// on ec-verlet: the pair loops, the cell lists' compactions and the walls on each level.
TEST(Isa, EveryLevelTheHostRunsGivesTheSameBytes) {
  const std::string cases = std::string(TWINFLOW_SOURCE_DIR) + "/cases/";
  const std::string short_run =
      " --set 'Particle/Equilibration steps=100' --set Particle/Steps=300";
  expect_same_bytes_on_every_level("cavity_2d", cases + "heated_cavity_2d.prm" + short_run);
  expect_same_bytes_on_every_level(
      "repulsive_3d", cases + "equilibrium_ideal_3d.prm --set 'Particle/Conservative force/Type=" +
                          "constant'" + short_run);
  expect_same_bytes_on_every_level(
      "ec_verlet_3d",
      cases + "equilibrium_ideal_3d.prm --set Particle/Integrator=ec-verlet" + short_run);
}

TEST(Isa, VersionNamesTheLevelAndAnUnknownOneIsRefused) {
  const Result version = run_twinflow("--version");
  ASSERT_EQ(version.code, 0) << version.output;
  EXPECT_NE(version.output.find("particle kernels: "), std::string::npos) << version.output;
  if (host_runs("baseline")) { // every build but a TWINFLOW_NATIVE one
    const Result baseline = run_twinflow("--version", "off", "TWINFLOW_ISA=baseline");
    EXPECT_NE(baseline.output.find("particle kernels: x86-64 (baseline)"), std::string::npos);
  }
  const fs::path dir = twinflow::testing::fresh_dir("isa_test", "refused");
  const Result r = run_twinflow("particle " + std::string(TWINFLOW_SOURCE_DIR) +
                                    "/cases/quickstart_2d.prm --out " + dir.string(),
                                "off", "TWINFLOW_ISA=sse1");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("TWINFLOW_ISA=sse1"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));
}
