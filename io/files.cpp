#include "io/files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <thread>

#include "io/isa.hpp"
#include "io/version.hpp"

namespace twinflow::io {

namespace fs = std::filesystem;

std::string cannot_write(const fs::path& path, int error_number) {
  return "cannot write " + path.string() + ": " + std::strerror(error_number);
}

void write_file_atomically(const fs::path& path, const std::string& content) {
  // A name of its own per process and call: concurrent writers of one path (two runs filling
  // the same cache entry) each rename a whole file.
  static std::atomic<unsigned> calls{0};
  fs::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(calls++);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) throw OutputError(cannot_write(path, errno));
  auto fail = [&](int error_number, bool open) {
    if (open) ::close(fd);
    ::unlink(tmp.c_str());
    throw OutputError(cannot_write(path, error_number));
  };
  const char* data = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(errno, true);
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) fail(errno, false); // NFS and quotas report here
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail(errno, false);
}

void remove_stale_temporaries(const fs::path& dir) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const auto at = name.rfind(".tmp");
    if (at == std::string::npos || at == 0) continue;
    const std::string tail = name.substr(at + 4); // "" or ".PID.N"
    if (!tail.empty() &&
        (tail[0] != '.' || tail.find_first_not_of(".0123456789") != std::string::npos))
      continue;
    std::error_code ignored;
    if (it->is_regular_file(ignored)) fs::remove(it->path(), ignored);
  }
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
  std::error_code ec;
  fs::create_directories(path_, ec);
  if (ec) throw OutputError("cannot create " + path_.string() + ": " + ec.message());
  remove_stale_temporaries(path_);
}

std::string content_hash(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull; // FNV-1a 64
  for (const unsigned char ch : text) h = (h ^ ch) * 1099511628211ull;
  std::ostringstream hex;
  hex << std::hex << std::setw(16) << std::setfill('0') << h;
  return hex.str();
}

std::string version_line() {
  return std::string("twinflow ") + kVersion + " (git " + kGitRevision + ", " + kCompiler + ", " +
         kBuildType + ")";
}

namespace {
// The value of /proc/cpuinfo's first "KEY : value" line ("" where there is none).
std::string cpuinfo_value(const std::string& cpuinfo, const std::string& key) {
  std::istringstream lines(cpuinfo);
  for (std::string line; std::getline(lines, line);) {
    const auto colon = line.find(':');
    if (colon == std::string::npos || line.rfind(key, 0) != 0) continue;
    const auto name_end = line.find_last_not_of(" \t", colon - 1);
    if (name_end + 1 != key.size()) continue; // "model" is not "model name"
    const auto value = line.find_first_not_of(' ', colon + 1);
    return value == std::string::npos ? "" : line.substr(value);
  }
  return "";
}
} // namespace

// The host as /proc/cpuinfo names it (CPU model, family and model numbers, the vector ISA flags
// the kernels care about) and its cores; "unknown" off Linux.
Json host_record() {
  std::ifstream file("/proc/cpuinfo");
  const std::string cpuinfo{std::istreambuf_iterator<char>(file), {}};
  const std::string model = cpuinfo_value(cpuinfo, "model name");
  std::string isa;
  const std::string flags = " " + cpuinfo_value(cpuinfo, "flags") + " ";
  for (const char* flag : {"avx2", "fma", "avx512f", "avx512vl"})
    if (flags.find(std::string(" ") + flag + " ") != std::string::npos)
      isa += (isa.empty() ? "" : " ") + std::string(flag);
  Json j = Json::object();
  j["cpu_model"] = model.empty() ? "unknown" : model;
  j["cpu_family"] = cpuinfo_value(cpuinfo, "cpu family");
  j["cpu_model_number"] = cpuinfo_value(cpuinfo, "model");
  j["isa_flags"] = isa.empty() ? "none of avx2 fma avx512f avx512vl" : isa;
  j["cores"] = static_cast<long>(std::thread::hardware_concurrency());
  return j;
}

std::string host_line() {
  const Json h = host_record();
  return "host: " + h["cpu_model"].get<std::string>() + " (family " +
         h["cpu_family"].get<std::string>() + ", model " +
         h["cpu_model_number"].get<std::string>() + "), " + std::to_string(h["cores"].get<long>()) +
         " cores, isa " + h["isa_flags"].get<std::string>();
}

Json provenance() {
  Json j = Json::object();
  j["twinflow_git_revision"] = kGitRevision;
  j["compiler"] = kCompiler;
  j["build_type"] = kBuildType;
  j["version"] = version_line();
  j["host"] = host_record();
  j["particle_kernels"] = isa_name(kernel_isa());
  return j;
}

} // namespace twinflow::io
