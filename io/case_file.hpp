#pragma once
// The case file: every parameter declared once (pattern, default, doc) in a deal.II
// ParameterHandler, read with a line parser that knows each value's file and line, so that
// every error names file, line, key and the allowed range.

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/files.hpp"

namespace twinflow::io {

class Registry {
public:
  static constexpr const char* kPositive = "a number > 0"; // what a positive number allows
  // path: "Particle/Dissipation/sigma"; `allowed` defaults to the pattern's description.
  void declare(const std::string& path, const std::string& default_value,
               const dealii::Patterns::PatternBase& pattern, const std::string& doc,
               const std::string& allowed = "");

  // A real number > 0 (the pattern Double(); get_positive checks the sign).
  void declare_positive(const std::string& path, const std::string& default_value,
                        const std::string& doc) {
    declare(path, default_value, dealii::Patterns::Double(), doc, kPositive);
  }

  void parse_file(const std::string& filename);
  void set_override(const std::string& assignment); // "Particle/Time step=0.01"

  std::string get(const std::string& path) const;
  double get_double(const std::string& path) const;
  long get_integer(const std::string& path) const;
  bool get_bool(const std::string& path) const;
  double get_positive(const std::string& path) const { // fails unless > 0
    const double value = get_double(path);
    require(value > 0, path, kPositive);
    return value;
  }
  std::vector<double> get_doubles(const std::string& path) const;

  // Semantic check failed: throws InputError naming where the value came from.
  [[noreturn]] void fail(const std::string& path, const std::string& allowed) const;
  void require(bool ok, const std::string& path, const std::string& allowed) const {
    if (!ok) fail(path, allowed);
  }

  void print_documented(std::ostream& out) const;
  void print_resolved(std::ostream& out) const;
  Json resolved_json() const; // every parameter's value, by path
  const std::string& default_value(const std::string& path) const; // as declared

private:
  struct Entry {
    std::unique_ptr<dealii::Patterns::PatternBase> pattern;
    std::string default_value, doc, allowed;
    std::string source = "default"; // "file:line", "--set" or "default"
  };
  void set_value(const std::string& path, const std::string& value, const std::string& where);
  void parse_stream(const std::string& filename, int depth, std::vector<std::string>& sections);
  dealii::ParameterHandler& enter(const std::string& path, std::string& key) const;
  void leave(const std::string& path) const;

  mutable dealii::ParameterHandler prm_;
  std::map<std::string, Entry> entries_;
  std::vector<std::string> order_;
  std::map<std::string, bool> subsections_;
  int statements_ = 0; // 'subsection' and 'set' lines read by parse_file, includes too
};

} // namespace twinflow::io
