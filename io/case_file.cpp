#include "io/case_file.hpp"

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace twinflow::io {

namespace {
std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream s(path);
  while (std::getline(s, part, '/')) parts.push_back(dealii::Utilities::trim(part));
  return parts;
}

std::string join(const std::vector<std::string>& parts, std::size_t n) {
  std::string out;
  for (std::size_t i = 0; i < n; ++i) out += (i ? "/" : "") + parts[i];
  return out;
}

std::string allowed_text(const dealii::Patterns::PatternBase& p) {
  std::string d = p.description(dealii::Patterns::PatternBase::Text);
  std::replace(d.begin(), d.end(), '\n', ' ');
  return d;
}
} // namespace

dealii::ParameterHandler& Registry::enter(const std::string& path, std::string& key) const {
  const auto parts = split_path(path);
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) prm_.enter_subsection(parts[i]);
  key = parts.back();
  return prm_;
}

void Registry::leave(const std::string& path) const {
  const auto parts = split_path(path);
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) prm_.leave_subsection();
}

void Registry::declare(const std::string& path, const std::string& default_value,
                       const dealii::Patterns::PatternBase& pattern, const std::string& doc,
                       const std::string& allowed) {
  std::string key;
  enter(path, key).declare_entry(key, default_value, pattern, doc);
  leave(path);
  entries_[path] =
      Entry{pattern.clone(), default_value, doc, allowed.empty() ? allowed_text(pattern) : allowed};
  order_.push_back(path);
  const auto parts = split_path(path);
  for (std::size_t n = 1; n < parts.size(); ++n) subsections_[join(parts, n)] = true;
}

void Registry::set_value(const std::string& path, const std::string& value,
                         const std::string& where) {
  const auto it = entries_.find(path);
  if (it == entries_.end())
    throw InputError(where + ": unknown parameter '" + path +
                     "' (twinflow print-parameters lists them all)");
  if (!it->second.pattern->match(value))
    throw InputError(where + ": '" + path + "' = '" + value +
                     "' is not allowed; allowed: " + it->second.allowed);
  std::string key;
  enter(path, key).set(key, value);
  leave(path);
  it->second.source = where;
}

namespace {
// Up to 40 characters of `line` with anything unprintable shown as \xNN (a binary file's
// message stays one readable line).
std::string printable_excerpt(const std::string& line, std::size_t length = 40) {
  std::string out;
  for (std::size_t i = 0; i < line.size() && i < length; ++i) {
    const auto ch = static_cast<unsigned char>(line[i]);
    if (ch >= 32 && ch < 127) {
      out += static_cast<char>(ch);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02X", ch);
      out += buf;
    }
  }
  if (line.size() > length) out += "...";
  return out;
}

// What a case path must be before its lines are read: an existing, non-empty regular file.
void require_case_file(const std::string& filename) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(filename, ec);
  if (!fs::exists(status))
    throw InputError(filename + ": cannot open case file for reading (no such file)");
  if (fs::is_directory(status))
    throw InputError(filename + ": is a directory, not a case file (give a .prm file)");
  if (!fs::is_regular_file(status))
    throw InputError(filename + ": is not a regular file (give a .prm file)");
  if (fs::file_size(filename, ec) == 0 && !ec)
    throw InputError(filename + ": is empty; a case file has 'subsection' and 'set' lines "
                                "(twinflow print-parameters prints one with every key)");
}
} // namespace

void Registry::parse_file(const std::string& filename) {
  require_case_file(filename);
  std::vector<std::string> sections;
  statements_ = 0;
  parse_stream(filename, 0, sections);
  if (statements_ == 0)
    throw InputError(filename + ": has no 'subsection' or 'set' line: not a case file "
                                "(twinflow print-parameters prints one with every key)");
}

void Registry::parse_stream(const std::string& filename, int depth,
                            std::vector<std::string>& sections) {
  if (depth > 8) throw InputError(filename + ": include nested too deeply");
  if (depth > 0) require_case_file(filename);
  std::ifstream in(filename, std::ios::binary);
  if (!in) throw InputError(filename + ": cannot open case file for reading");
  const std::size_t base_depth = sections.size();
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string where = filename + ":" + std::to_string(number);
    if (line.find('\0') != std::string::npos)
      throw InputError(where + ": a binary file, not a case file (starts '" +
                       printable_excerpt(line) + "')");
    if (!line.empty() && line.back() == '\r') line.pop_back(); // written on Windows
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    line = dealii::Utilities::trim(line);
    if (line.empty()) continue;
    const auto space = line.find_first_of(" \t");
    const std::string word = line.substr(0, space);
    const std::string rest =
        space == std::string::npos ? "" : dealii::Utilities::trim(line.substr(space));
    if (word == "subsection" || word == "set") ++statements_;
    if (word == "subsection") {
      sections.push_back(rest);
      if (!subsections_.count(join(sections, sections.size())))
        throw InputError(where + ": unknown subsection '" + join(sections, sections.size()) + "'");
    } else if (word == "end") {
      if (sections.size() <= base_depth)
        throw InputError(where + ": 'end' without a matching 'subsection'");
      sections.pop_back();
    } else if (word == "set") {
      const auto eq = rest.find('=');
      if (eq == std::string::npos)
        throw InputError(where + ": expected 'set KEY = VALUE', got '" + line + "'");
      const std::string key = dealii::Utilities::trim(rest.substr(0, eq));
      const std::string value = dealii::Utilities::trim(rest.substr(eq + 1));
      const std::string prefix = join(sections, sections.size());
      set_value(prefix.empty() ? key : prefix + "/" + key, value, where);
    } else if (word == "include") {
      // Relative to the including file, as in ASPECT's test cases.
      std::filesystem::path inc(rest);
      if (inc.is_relative()) inc = std::filesystem::path(filename).parent_path() / inc;
      parse_stream(inc.string(), depth + 1, sections);
    } else {
      throw InputError(where + ": cannot read line '" + printable_excerpt(line, 200) +
                       "' (expected subsection, end, set or include)");
    }
  }
  if (sections.size() != base_depth)
    throw InputError(filename + ": subsection '" + sections.back() + "' has no 'end'");
}

void Registry::set_override(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos) throw InputError("--set " + assignment + ": expected KEY=VALUE");
  std::string path;
  for (const auto& p : split_path(assignment.substr(0, eq))) path += (path.empty() ? "" : "/") + p;
  set_value(path, dealii::Utilities::trim(assignment.substr(eq + 1)), "--set " + assignment);
}

std::string Registry::get(const std::string& path) const {
  std::string key;
  const std::string v = enter(path, key).get(key);
  leave(path);
  return v;
}

double Registry::get_double(const std::string& path) const {
  return dealii::Utilities::string_to_double(get(path));
}
long Registry::get_integer(const std::string& path) const {
  return std::stol(get(path));
}
bool Registry::get_bool(const std::string& path) const {
  const std::string v = get(path);
  return v == "true" || v == "yes";
}
std::vector<double> Registry::get_doubles(const std::string& path) const {
  return dealii::Utilities::string_to_double(dealii::Utilities::split_string_list(get(path)));
}

void Registry::fail(const std::string& path, const std::string& allowed) const {
  const auto it = entries_.find(path);
  const std::string where = it == entries_.end() ? "case" : it->second.source;
  throw InputError(where + ": '" + path + "' = '" + get(path) +
                   "' is not allowed; allowed: " + allowed);
}

// In .prm syntax, so the output is itself a valid case file.
void Registry::print_documented(std::ostream& out) const {
  std::vector<std::string> open;
  for (const auto& path : order_) {
    auto parts = split_path(path);
    const std::string key = parts.back();
    parts.pop_back();
    std::size_t common = 0;
    while (common < open.size() && common < parts.size() && open[common] == parts[common]) ++common;
    while (open.size() > common) {
      open.pop_back();
      out << std::string(2 * open.size(), ' ') << "end\n";
    }
    for (std::size_t i = common; i < parts.size(); ++i) {
      out << "\n" << std::string(2 * open.size(), ' ') << "subsection " << parts[i] << "\n";
      open.push_back(parts[i]);
    }
    const Entry& e = entries_.at(path);
    const std::string pad(2 * open.size(), ' ');
    std::istringstream doc(e.doc);
    std::string word, line;
    while (doc >> word) { // wrap at ~90 columns
      if (line.size() + word.size() > 88 - pad.size()) {
        out << pad << "#" << line << "\n";
        line.clear();
      }
      line += " " + word;
    }
    if (!line.empty()) out << pad << "#" << line << "\n";
    out << pad << "#  allowed: " << e.allowed << "\n";
    out << pad << "set " << key << " = " << e.default_value << "\n\n";
  }
  while (!open.empty()) {
    open.pop_back();
    out << std::string(2 * open.size(), ' ') << "end\n";
  }
}

void Registry::print_resolved(std::ostream& out) const {
  prm_.print_parameters(out, dealii::ParameterHandler::ShortPRM |
                                 dealii::ParameterHandler::KeepDeclarationOrder);
}

const std::string& Registry::default_value(const std::string& path) const {
  return entries_.at(path).default_value;
}

Json Registry::resolved_json() const {
  Json j = Json::object();
  for (const auto& path : order_) j[path] = get(path);
  return j;
}

} // namespace twinflow::io
