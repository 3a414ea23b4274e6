#pragma once
// Where results go and how they are written: atomically, under a run directory.

#include <filesystem>
#include <stdexcept>
#include <string>

#include "io/json.hpp"

namespace twinflow::io {

// Bad input from the user (case file, option, run directory): the front end exits with code 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Writes to `path.tmp` and renames, so an interrupted run never leaves a half-written file.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);
std::string read_file(const std::filesystem::path& path); // throws InputError

// A stage's folder in the run directory (e.g. RUNDIR/particle). A stage whose summary.json
// exists is a finished earlier result: it is not overwritten unless `force`.
class StageDirectory {
public:
  StageDirectory(const std::filesystem::path& run_dir, const std::string& stage, bool force);
  // Creates the folder; call only once all inputs are validated (bad input writes nothing).
  void create() const;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path file(const std::string& name) const { return path_ / name; }

private:
  std::filesystem::path path_;
};

// Fields every stage's summary.json carries: versions, git revision.
Json provenance();

// FNV-1a 64 of `text` as 16 hex digits: names results by their inputs (stage reuse, caches).
std::string content_hash(const std::string& text);

} // namespace twinflow::io
