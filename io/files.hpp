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

// An output could not be written (disk full, permission denied, read-only file system, file
// size limit): the front end exits with kExitOutputFailed (6). The message names the file and
// the operating system's reason ("No space left on device").
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Writes to `path.tmp.PID.N` in the same directory and renames it over `path` only once every
// byte is written and the file closed, so no incomplete file ever sits under `path`. On failure
// the temporary file is removed and OutputError names `path` and the OS reason.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);
// "cannot write FILE: REASON" for an errno value (the message of OutputError).
std::string cannot_write(const std::filesystem::path& path, int error_number);
// Removes temporary files (NAME.tmp, NAME.tmp.PID.N) an earlier killed run left in `dir`.
void remove_stale_temporaries(const std::filesystem::path& dir);
std::string read_file(const std::filesystem::path& path); // throws InputError

// A stage's folder in the run directory (e.g. RUNDIR/particle). A stage whose summary.json
// exists is a finished earlier result: it is not overwritten unless `force`.
class StageDirectory {
public:
  StageDirectory(const std::filesystem::path& run_dir, const std::string& stage, bool force);
  // Creates the folder (and removes the temporary files of an earlier killed run in it); call
  // only once all inputs are validated (bad input writes nothing).
  void create() const;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path file(const std::string& name) const { return path_ / name; }

private:
  std::filesystem::path path_;
};

// Fields every stage's summary.json carries. What made a result: the git revision, compiler, build
// type, --version's line and the host (host_record()).
Json provenance();
// The host: CPU model, family and model numbers, the avx2/fma/avx512f/avx512vl flags, cores.
Json host_record();
// host_record() as --version's line: "host: MODEL (family F, model M), C cores, isa FLAGS".
std::string host_line();
// "twinflow 0.1.0 (git REV, COMPILER, BUILD TYPE)" and "HDF5 1.10.8": for --version.
std::string version_line();
std::string hdf5_version();

// FNV-1a 64 of `text` as 16 hex digits: names results by their inputs (stage reuse, caches).
std::string content_hash(const std::string& text);

} // namespace twinflow::io
