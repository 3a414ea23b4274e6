#pragma once
// What a stage's results depend on, and their reuse: the case record's values of the stage's
// sections and the upstream stages' hashes, hashed (FNV-1a 64) and written next to the results
// as inputs.json. `run` reuses a stage whose inputs are unchanged. The code revision is recorded
// but not hashed: an upgrade does not throw away hours of particle data (`run` says when it
// reuses another revision's results; --force recomputes).

#include <filesystem>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "io/json.hpp"
#include "study/case.hpp"

namespace twinflow::study {

struct StageInputs {
  io::Json inputs = io::Json::object();
  std::string hash;
  io::Json defaults = io::Json::object(); // of the hashed parameters
};

// `sections`: prefixes of the record's paths ("Scene/", ...); `method`: a measurement's version
// (a changed method is not reused; 0: none).
StageInputs stage_inputs(const Case& c, std::initializer_list<const char*> sections,
                         const std::vector<std::string>& upstream_hashes, int method = 0);

// The stage's earlier results are complete and were made from the same inputs (a record made
// before a parameter existed lacks it: the same inputs if it has its default).
bool reusable(const std::filesystem::path& stage_dir, const StageInputs& s);

// Which ranks run a stage under mpirun (study/ranks.hpp): all of them (its particle runs are
// split over them), or rank 0 alone (a serial stage).
enum class Ranks { Every, Zero };

// Runs a stage unless its inputs are unchanged (or `force`); records its inputs after it
// succeeds. Returns the stage's exit code. Rank 0 decides and writes the record.
int run_or_reuse(const std::filesystem::path& stage_dir, const StageInputs& s, bool force,
                 const std::function<int()>& stage, Ranks ranks = Ranks::Zero);

} // namespace twinflow::study
