#include "io/json.hpp"

#include <cmath>

#include "io/files.hpp"

namespace twinflow::io {

namespace {
template <class Keys> const Json* find_path(const Json& j, const Keys& path) {
  const Json* v = &j;
  for (const auto& key : path) {
    if (!v->is_object()) return nullptr;
    const auto it = v->find(std::string(key));
    if (it == v->end()) return nullptr;
    v = &*it;
  }
  return v;
}
} // namespace

const Json* find(const Json& j, std::initializer_list<std::string_view> path) {
  return find_path(j, path);
}

const Json* find(const Json& j, const std::vector<std::string>& path) {
  return find_path(j, path);
}

double number(const Json& j, std::initializer_list<std::string_view> path) {
  const Json* v = find(j, path);
  return v && v->is_number() ? v->get<double>() : std::nan("");
}

std::string text(const Json& j, std::initializer_list<std::string_view> path,
                 const std::string& fallback) {
  const Json* v = find(j, path);
  return v && v->is_string() ? v->get<std::string>() : fallback;
}

Json read_json(const std::filesystem::path& file, const std::string& if_missing) {
  if (!std::filesystem::exists(file))
    throw InputError(file.string() + ": missing" + (if_missing.empty() ? "" : "; " + if_missing));
  try {
    return Json::parse(read_file(file));
  } catch (const Json::parse_error& e) {
    throw InputError(file.string() + ": not valid JSON (" + e.what() + ")");
  }
}

std::string dump(const Json& j) {
  return j.dump(2) + "\n";
}

} // namespace twinflow::io
