#pragma once
// Saving and restoring a run's state through one list of members: a component writes
// `template <class A> void archive(A& a) { a("x", x_); a("step", step_); ... }` once, and the
// same list serves SaveArchive (into a checkpoint) and LoadArchive (out of one), so the two can
// never disagree. Doubles travel as raw bytes: a restart continues bitwise.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/files.hpp"

namespace twinflow::particle {

class SaveArchive {
public:
  SaveArchive(io::Checkpoint& c, std::string prefix) : c_(c), prefix_(std::move(prefix)) {}
  static constexpr bool loading = false;

  void operator()(const std::string& name, const double& v) { c_.put(key(name), v); }
  void operator()(const std::string& name, const long& v) { c_.put(key(name), v); }
  void operator()(const std::string& name, const std::string& v) { c_.put(key(name), v); }
  void operator()(const std::string& name, const std::vector<double>& v) { c_.put(key(name), v); }
  void operator()(const std::string& name, const std::vector<long>& v) {
    c_.put(key(name), std::vector<std::int64_t>(v.begin(), v.end()));
  }
  void operator()(const std::string& name, const std::vector<std::uint32_t>& v) {
    c_.put(key(name), std::vector<std::uint64_t>(v.begin(), v.end()));
  }
  template <std::size_t N>
  void operator()(const std::string& name, const std::array<double, N>& v) {
    c_.put(key(name), std::vector<double>(v.begin(), v.end()));
  }
  template <std::size_t N>
  void operator()(const std::string& name, const std::array<std::vector<double>, N>& v) {
    for (std::size_t d = 0; d < N; ++d) (*this)(name + "." + std::to_string(d), v[d]);
  }
  template <std::size_t N> // floats travel as doubles (exact both ways)
  void operator()(const std::string& name, const std::array<std::vector<float>, N>& v) {
    for (std::size_t d = 0; d < N; ++d)
      (*this)(name + "." + std::to_string(d), std::vector<double>(v[d].begin(), v[d].end()));
  }
  void operator()(const std::string& name, const std::vector<std::vector<double>>& v) {
    (*this)(name + ".count", static_cast<long>(v.size()));
    for (std::size_t k = 0; k < v.size(); ++k) (*this)(name + "." + std::to_string(k), v[k]);
  }
  SaveArchive nested(const std::string& name) const { return SaveArchive(c_, key(name) + "/"); }

private:
  std::string key(const std::string& name) const { return prefix_ + name; }
  io::Checkpoint& c_;
  std::string prefix_;
};

class LoadArchive {
public:
  LoadArchive(const io::Checkpoint& c, std::string prefix) : c_(c), prefix_(std::move(prefix)) {}
  static constexpr bool loading = true;

  void operator()(const std::string& name, double& v) { v = c_.get<double>(key(name)); }
  void operator()(const std::string& name, long& v) {
    v = static_cast<long>(c_.get<std::int64_t>(key(name)));
  }
  void operator()(const std::string& name, std::string& v) { v = c_.get<std::string>(key(name)); }
  void operator()(const std::string& name, std::vector<double>& v) {
    v = c_.get<std::vector<double>>(key(name));
  }
  void operator()(const std::string& name, std::vector<long>& v) {
    const auto w = c_.get<std::vector<std::int64_t>>(key(name));
    v.assign(w.begin(), w.end());
  }
  void operator()(const std::string& name, std::vector<std::uint32_t>& v) {
    const auto w = c_.get<std::vector<std::uint64_t>>(key(name));
    v.assign(w.begin(), w.end());
  }
  template <std::size_t N> void operator()(const std::string& name, std::array<double, N>& v) {
    const auto w = c_.get<std::vector<double>>(key(name));
    if (w.size() != N) throw io::InputError("checkpoint record " + key(name) + " has wrong size");
    for (std::size_t k = 0; k < N; ++k) v[k] = w[k];
  }
  template <std::size_t N>
  void operator()(const std::string& name, std::array<std::vector<double>, N>& v) {
    for (std::size_t d = 0; d < N; ++d) (*this)(name + "." + std::to_string(d), v[d]);
  }
  template <std::size_t N>
  void operator()(const std::string& name, std::array<std::vector<float>, N>& v) {
    for (std::size_t d = 0; d < N; ++d) {
      const auto w = c_.get<std::vector<double>>(key(name + "." + std::to_string(d)));
      v[d].assign(w.begin(), w.end());
    }
  }
  void operator()(const std::string& name, std::vector<std::vector<double>>& v) {
    long count = 0;
    (*this)(name + ".count", count);
    v.assign(static_cast<std::size_t>(count), {});
    for (std::size_t k = 0; k < v.size(); ++k) (*this)(name + "." + std::to_string(k), v[k]);
  }
  LoadArchive nested(const std::string& name) const { return LoadArchive(c_, key(name) + "/"); }

private:
  std::string key(const std::string& name) const { return prefix_ + name; }
  const io::Checkpoint& c_;
  std::string prefix_;
};

} // namespace twinflow::particle
