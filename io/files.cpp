#include "io/files.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "io/version.hpp"

namespace twinflow::io {

namespace fs = std::filesystem;

void write_file_atomically(const fs::path& path, const std::string& content) {
  // A name of its own per process and call: concurrent writers of one path (two runs filling
  // the same cache entry) each rename a whole file.
  static std::atomic<unsigned> calls{0};
  fs::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(calls++);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    out << content;
    out.flush();
    if (!out) throw std::runtime_error("error writing " + tmp.string());
  }
  fs::rename(tmp, path);
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open file for reading");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

StageDirectory::StageDirectory(const fs::path& run_dir, const std::string& stage, bool force)
    : path_(run_dir / stage) {
  if (fs::exists(path_ / "summary.json") && !force)
    throw InputError(path_.string() +
                     ": holds an earlier run's results; use --force to overwrite or another --out");
  if (fs::exists(run_dir) && !fs::is_directory(run_dir))
    throw InputError(run_dir.string() + ": exists and is not a directory");
}

void StageDirectory::create() const {
  fs::create_directories(path_);
}

std::string content_hash(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull; // FNV-1a 64
  for (const unsigned char ch : text) h = (h ^ ch) * 1099511628211ull;
  std::ostringstream hex;
  hex << std::hex << std::setw(16) << std::setfill('0') << h;
  return hex.str();
}

Json provenance() {
  Json j = Json::object();
  j["twinflow_git_revision"] = kGitRevision;
  j["compiler"] = kCompiler;
  j["build_type"] = kBuildType;
  return j;
}

} // namespace twinflow::io
