#pragma once
// JSON through nlohmann-json (Debian nlohmann-json3-dev). Objects keep their keys in insertion
// order, so a summary.json reads in the order it was written. Non-finite numbers are written as
// null (JSON has no NaN) and read back as NaN by number().

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace twinflow::io {

using Json = nlohmann::ordered_json;

// The one lookup: the value at a path of nested object keys; nullptr where a key is absent or a
// step is not an object.
const Json* find(const Json& j, std::initializer_list<std::string_view> path);
const Json* find(const Json& j, const std::vector<std::string>& path);
// A std::string would silently become a JSON string here; its own find() is meant.
const Json* find(const std::string&, std::initializer_list<std::string_view>) = delete;
// Its number; NaN where absent, null or not a number.
double number(const Json& j, std::initializer_list<std::string_view> path);
// Its string; `fallback` where absent or not a string.
std::string text(const Json& j, std::initializer_list<std::string_view> path,
                 const std::string& fallback = "");

// The one reader: the parsed file. Throws InputError naming the file when it is missing
// (followed by `if_missing`: what to do about it), unreadable or not JSON.
Json read_json(const std::filesystem::path& file, const std::string& if_missing = "");
// As twinflow writes its files: two-space indent, a final newline.
std::string dump(const Json& j);

} // namespace twinflow::io
