// The typed record of the resolved case (study/case_record.hpp, RUNDIR/case.json): every shipped
// case reads back member for member, through the file's text; an absent member takes its
// default; `compare RUNDIR`'s --set takes Compare/ keys only.

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <string>

#include "io/files.hpp"
#include "io/json_fields.hpp"
#include "run_twinflow.hpp"
#include "study/case_file/case_file.hpp"
#include "study/case_record.hpp"

namespace fs = std::filesystem;
using twinflow::io::Json;
using namespace twinflow::study;

namespace {
struct Three {
  int a = 1;
  std::array<double, 3> b{{1, 2, 3}};
  std::string c = "c";
};
} // namespace
static_assert(twinflow::io::detail::member_count<Three>() == 3);
static_assert(twinflow::io::detail::name_count("a, b, c") == 3);

// Every shipped case: its parameters through case.json's text come back with every member equal
// (the JSON names every member, so equal JSON is equal structs).
TEST(CaseRecord, EveryShippedCaseReadsBackMemberForMember) {
  int cases = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(TWINFLOW_SOURCE_DIR) / "cases")) {
    if (entry.path().extension() != ".prm") continue;
    const Case c = CaseFile().load(entry.path().string(), {});
    const Json written = case_parameters_json(c.parameters);
    const Json read_back =
        case_parameters_json(case_parameters_from_json(Json::parse(twinflow::io::dump(written))));
    EXPECT_EQ(read_back, written) << entry.path();
    EXPECT_EQ(read_back.at("particle").at("seed"), c.parameters.particle.seed);
    ++cases;
  }
  EXPECT_GT(cases, 20);
}

TEST(CaseRecord, RunDirectoryRecordRoundTripsAndRefusesWhatItCannotRead) {
  const fs::path dir = twinflow::testing::fresh_dir("case_record_test", "round_trip");
  fs::create_directories(dir);
  EXPECT_THROW(read_case_record(dir), twinflow::io::InputError); // no case.json yet
  Case c = CaseFile().load(std::string(TWINFLOW_SOURCE_DIR) + "/cases/quickstart_2d.prm",
                           {"Particle/Seed=7"});
  c.parameters.transport.temperature = 0.8871234567891234; // a number no text rounded
  write_case_record(c, dir);
  const Case back = read_case_record(dir);
  EXPECT_EQ(back.parameters.transport.temperature, c.parameters.transport.temperature);
  EXPECT_EQ(back.parameters.particle.seed, 7u);
  EXPECT_EQ(case_parameters_json(back.parameters), case_parameters_json(c.parameters));
  EXPECT_EQ(back.record, c.record);
  EXPECT_EQ(back.settings, c.settings);

  // A member absent from the record (written before it existed) takes its default.
  Json j = twinflow::io::read_json(case_record_file(dir));
  j["parameters"]["particle"].erase("blocks");
  j["parameters"]["particle"]["steps"] = 123;
  twinflow::io::write_file_atomically(case_record_file(dir), twinflow::io::dump(j));
  const Case older = read_case_record(dir);
  EXPECT_EQ(older.parameters.particle.blocks, twinflow::particle::ParticleParameters{}.blocks);
  EXPECT_EQ(older.parameters.particle.steps, 123);

  // A member of the wrong type, or another layout's version: refused, naming the file.
  j["parameters"]["particle"]["steps"] = "many";
  twinflow::io::write_file_atomically(case_record_file(dir), twinflow::io::dump(j));
  EXPECT_THROW(read_case_record(dir), twinflow::io::InputError);
  j["parameters"]["particle"]["steps"] = 123;
  j["format"] = 99;
  twinflow::io::write_file_atomically(case_record_file(dir), twinflow::io::dump(j));
  EXPECT_THROW(read_case_record(dir), twinflow::io::InputError);
}

// `compare RUNDIR --set`: Compare/ keys over the recorded case, through the case file's own
// checks; other sections would change the twins already run.
TEST(CaseRecord, CompareTakesCompareKeysOverTheRecord) {
  const fs::path dir = twinflow::testing::fresh_dir("case_record_test", "compare_keys");
  fs::create_directories(dir);
  const Case c = CaseFile().load(std::string(TWINFLOW_SOURCE_DIR) + "/cases/quickstart_2d.prm",
                                 {"Compare/Wall slip=false"});
  write_case_record(c, dir);
  const Case same = recorded_case(dir, {});
  EXPECT_EQ(case_parameters_json(same.parameters), case_parameters_json(c.parameters));
  const Case wider = recorded_case(dir, {"Compare/Wall layer=2"});
  EXPECT_EQ(wider.parameters.compare.wall_layer, 2.0);
  EXPECT_FALSE(wider.parameters.compare.wall_slip); // the recorded value stays
  EXPECT_EQ(wider.record.at("Compare/Wall layer"), "2");
  EXPECT_THROW(recorded_case(dir, {"Compare/Wall layer=-1"}), twinflow::io::InputError);
  EXPECT_THROW(recorded_case(dir, {"Particle/Seed=3"}), twinflow::io::InputError);
  EXPECT_THROW(recorded_case(dir, {"Continuum/Mesh/Cells=4"}), twinflow::io::InputError);
}
