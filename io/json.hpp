#pragma once
// A small ordered JSON value: enough to write summary.json and metrics.json.

#include <cstdint>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace twinflow::io {

class Json {
public:
  using Array = std::vector<Json>;
  using Object = std::vector<std::pair<std::string, Json>>; // insertion order kept

  Json() : value_(nullptr) {}
  Json(std::nullptr_t) : value_(nullptr) {}
  Json(bool b) : value_(b) {}
  Json(int v) : value_(static_cast<double>(v)) {}
  Json(long v) : value_(static_cast<double>(v)) {}
  Json(long long v) : value_(static_cast<double>(v)) {}
  Json(unsigned v) : value_(static_cast<double>(v)) {}
  Json(unsigned long v) : value_(static_cast<double>(v)) {}
  Json(unsigned long long v) : value_(static_cast<double>(v)) {}
  Json(double v) : value_(v) {}
  Json(const char* s) : value_(std::string(s)) {}
  Json(std::string s) : value_(std::move(s)) {}
  Json(Array a) : value_(std::move(a)) {}
  Json(const std::vector<double>& v) : value_(Array(v.begin(), v.end())) {}

  static Json object() {
    Json j;
    j.value_ = Object{};
    return j;
  }
  static Json array() {
    Json j;
    j.value_ = Array{};
    return j;
  }

  // Object access: inserts the key if absent (turns null into an object).
  Json& operator[](const std::string& key);
  // Pointers and references into a Json live as long as it: on a temporary they would dangle, so
  // the compiler refuses (e.g. Json::parse(text).find(key)).
  const Json* find(const std::string& key) const&;
  const Json* find(const std::string& key) const&& = delete;
  void push_back(Json v);

  bool is_null() const { return std::holds_alternative<std::nullptr_t>(value_); }
  bool is_object() const { return std::holds_alternative<Object>(value_); }
  bool is_number() const { return std::holds_alternative<double>(value_); }
  bool is_string() const { return std::holds_alternative<std::string>(value_); }
  bool is_array() const { return std::holds_alternative<Array>(value_); }
  double number() const { return std::get<double>(value_); }
  const std::string& string() const& { return std::get<std::string>(value_); }
  const std::string& string() const&& = delete;
  const Object& items() const& { return std::get<Object>(value_); }
  const Object& items() const&& = delete;
  const Array& elements() const& { return std::get<Array>(value_); }
  const Array& elements() const&& = delete;

  void write(std::ostream& out, int indent = 0) const;
  std::string dump() const;
  static Json parse(const std::string& text); // throws std::runtime_error

private:
  std::variant<std::nullptr_t, bool, double, std::string, Array, Object> value_;
};

} // namespace twinflow::io
