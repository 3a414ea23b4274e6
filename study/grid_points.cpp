#include "study/grid.hpp"

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>

#include "io/files.hpp"

// The grid's points: the --vary options read and checked against the case, and their Cartesian
// product, each point loaded through the case.
namespace twinflow::study {

namespace fs = std::filesystem;

namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

// "Particle / Time step" -> "Particle/Time step", as the case's --set reads it.
std::string canonical_key(const std::string& text) {
  std::string key, part;
  std::istringstream parts(text);
  while (std::getline(parts, part, '/')) key += (key.empty() ? "" : "/") + trim(part);
  return key;
}

std::vector<std::string> split_items(const std::string& list) {
  std::vector<std::string> items;
  std::string item;
  std::istringstream s(list);
  while (std::getline(s, item, ',')) items.push_back(trim(item));
  if (!list.empty() && list.back() == ',') items.emplace_back(); // "a,b," has an empty last item
  return items;
}

// "0 -0.01" -> "0, -0.01": a vector value's components, as the case's lists take them.
std::string joined_components(const std::string& item) {
  std::istringstream s(item);
  std::string component, out;
  while (s >> component) out += (out.empty() ? "" : ", ") + component;
  return out;
}

// Reads the case with these assignments; returns the message of the first error ("" if none).
std::string read_error(const GridOptions& o, const CaseReader& reader,
                       const std::vector<std::string>& extra) {
  std::vector<std::string> settings = o.settings;
  settings.insert(settings.end(), extra.begin(), extra.end());
  try {
    reader.check(settings);
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

} // namespace

io::Json grid_description(const GridOptions& o, const CaseReader& reader,
                          const std::vector<Axis>& axes) {
  io::Json grid = io::Json::object();
  grid["case_file"] = std::filesystem::absolute(o.case_file).lexically_normal().string();
  grid["base_parameters"] = reader.record(o.settings);
  grid["vary"] = io::Json::object();
  for (const auto& a : axes) {
    grid["vary"][a.key] = io::Json::array();
    for (const auto& v : a.shown) grid["vary"][a.key].push_back(v);
  }
  return grid;
}

std::vector<Axis> parse_axes(const GridOptions& o, const CaseReader& reader) {
  reader.check(
      o.settings); // the case file and the user's --set first: their errors name themselves
  std::vector<Axis> axes;
  for (const auto& text : o.vary) {
    const std::string where = "--vary '" + text + "'";
    const auto eq = text.find('=');
    if (eq == std::string::npos || trim(text.substr(0, eq)).empty())
      throw io::InputError(where + ": expected 'Section/Key=V1,V2,...'");
    Axis axis;
    axis.key = canonical_key(text.substr(0, eq));
    for (const auto& other : axes)
      if (other.key == axis.key)
        throw io::InputError(where + ": '" + axis.key +
                             "' is varied twice; give all its values in one --vary");
    for (const auto& item : split_items(text.substr(eq + 1))) {
      if (item.empty())
        throw io::InputError(where + ": an empty value; allowed: values separated by commas, " +
                             "vector components by spaces ('Scene/Gravity=0 -0.01,0 -0.02')");
      std::string value = item;
      std::string error = read_error(o, reader, {axis.key + "=" + value});
      if (!error.empty() && item.find_first_of(" \t") != std::string::npos &&
          read_error(o, reader, {axis.key + "=" + joined_components(item)}).empty()) {
        value = joined_components(item); // a vector value: components were separated by spaces
        error.clear();
      }
      if (!error.empty()) {
        // Name the --vary option rather than the --set it became.
        const std::string as_set = "--set " + axis.key + "=" + value + ": ";
        if (error.rfind(as_set, 0) == 0) error = error.substr(as_set.size());
        throw io::InputError(where + " (value '" + item + "'): " + error);
      }
      axis.shown.push_back(item);
      axis.values.push_back(value);
    }
    axes.push_back(axis);
  }
  return axes;
}

std::vector<Point> make_points(const GridOptions& o, const CaseReader& reader,
                               const std::vector<Axis>& axes, std::size_t copies) {
  std::size_t combinations = 1;
  for (const auto& a : axes) combinations *= a.values.size();
  const std::size_t total = combinations * copies;
  const std::size_t width = std::max<std::size_t>(3, std::to_string(total - 1).size());
  std::vector<Point> points;
  std::size_t rejected = 0;
  for (std::size_t combination = 0; combination < combinations; ++combination) {
    Point p;
    p.value_index.resize(axes.size());
    std::size_t rest = combination;
    for (std::size_t a = axes.size(); a-- > 0;) { // the first axis varies slowest
      p.value_index[a] = rest % axes[a].values.size();
      rest /= axes[a].values.size();
    }
    for (std::size_t a = 0; a < axes.size(); ++a)
      p.assignments.push_back(axes[a].key + "=" + axes[a].values[p.value_index[a]]);
    std::vector<std::string> settings = o.settings;
    settings.insert(settings.end(), p.assignments.begin(), p.assignments.end());
    try { // every value passed on its own (parse_axes): only their combination can fail
      p.resolved = reader.load(settings).parameters;
    } catch (const io::InputError& e) {
      p.rejected = e.what();
      for (const auto& a : p.assignments) // name the --vary the value came from
        if (p.rejected.rfind("--set " + a + ": ", 0) == 0)
          p.rejected = "--vary " + p.rejected.substr(6);
      ++rejected;
    }
    for (std::size_t copy = 0; copy < copies; ++copy) {
      std::string name = std::to_string(points.size());
      p.name = std::string(width - name.size(), '0') + name;
      points.push_back(p);
    }
  }
  if (rejected == combinations)
    throw io::InputError("no point of the grid is a valid case; the first: " +
                         points.front().rejected);
  return points;
}

} // namespace twinflow::study
