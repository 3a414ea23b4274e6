#include "io/json.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace twinflow::io {

Json& Json::operator[](const std::string& key) {
  if (std::holds_alternative<std::nullptr_t>(value_)) value_ = Object{};
  auto& obj = std::get<Object>(value_);
  for (auto& [k, v] : obj)
    if (k == key) return v;
  obj.emplace_back(key, Json());
  return obj.back().second;
}

const Json* Json::find(const std::string& key) const& {
  if (!is_object()) return nullptr;
  for (const auto& [k, v] : std::get<Object>(value_))
    if (k == key) return &v;
  return nullptr;
}

void Json::push_back(Json v) {
  if (std::holds_alternative<std::nullptr_t>(value_)) value_ = Array{};
  std::get<Array>(value_).push_back(std::move(v));
}

namespace {
void write_string(std::ostream& out, const std::string& s) {
  out << '"';
  for (const char c : s) {
    switch (c) {
    case '"':
      out << "\\\"";
      break;
    case '\\':
      out << "\\\\";
      break;
    case '\n':
      out << "\\n";
      break;
    case '\t':
      out << "\\t";
      break;
    case '\r':
      out << "\\r";
      break;
    default:
      if (static_cast<unsigned char>(c) < 0x20) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\u%04x", c);
        out << buf;
      } else {
        out << c;
      }
    }
  }
  out << '"';
}

void write_number(std::ostream& out, double v) {
  if (!std::isfinite(v)) { // JSON has no inf/nan; null keeps the file valid
    out << "null";
    return;
  }
  if (v == std::floor(v) && std::fabs(v) < 1e15) {
    out << static_cast<long long>(v);
    return;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  out << buf;
}
} // namespace

void Json::write(std::ostream& out, int indent) const {
  const std::string pad(indent + 2, ' '), end_pad(indent, ' ');
  if (std::holds_alternative<std::nullptr_t>(value_))
    out << "null";
  else if (auto b = std::get_if<bool>(&value_))
    out << (*b ? "true" : "false");
  else if (auto d = std::get_if<double>(&value_))
    write_number(out, *d);
  else if (auto s = std::get_if<std::string>(&value_))
    write_string(out, *s);
  else if (auto a = std::get_if<Array>(&value_)) {
    bool scalars = true;
    for (const auto& e : *a)
      scalars = scalars && !e.is_object() && !std::holds_alternative<Array>(e.value_);
    out << '[';
    for (std::size_t i = 0; i < a->size(); ++i) {
      if (i) out << (scalars ? ", " : ",");
      if (!scalars) out << '\n' << pad;
      (*a)[i].write(out, indent + 2);
    }
    if (!scalars && !a->empty()) out << '\n' << end_pad;
    out << ']';
  } else {
    const auto& o = std::get<Object>(value_);
    out << '{';
    for (std::size_t i = 0; i < o.size(); ++i) {
      out << (i ? ",\n" : "\n") << pad;
      write_string(out, o[i].first);
      out << ": ";
      o[i].second.write(out, indent + 2);
    }
    if (!o.empty()) out << '\n' << end_pad;
    out << '}';
  }
}

std::string Json::dump() const {
  std::ostringstream s;
  write(s);
  s << '\n';
  return s.str();
}

namespace {
struct Parser {
  const std::string& t;
  std::size_t p = 0;
  [[noreturn]] void fail(const char* what) const {
    throw std::runtime_error("JSON parse error at offset " + std::to_string(p) + ": " + what);
  }
  void skip() {
    while (p < t.size() && std::isspace(static_cast<unsigned char>(t[p]))) ++p;
  }
  bool eat(char c) {
    skip();
    if (p < t.size() && t[p] == c) {
      ++p;
      return true;
    }
    return false;
  }
  std::string str() {
    if (!eat('"')) fail("expected string");
    std::string s;
    while (p < t.size() && t[p] != '"') {
      char c = t[p++];
      if (c == '\\' && p < t.size()) {
        const char e = t[p++];
        c = e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e;
        if (e == 'u') { // only the control characters we write ourselves
          c = static_cast<char>(std::stoi(t.substr(p, 4), nullptr, 16));
          p += 4;
        }
      }
      s += c;
    }
    if (!eat('"')) fail("unterminated string");
    return s;
  }
  Json value() {
    skip();
    if (p >= t.size()) fail("unexpected end");
    const char c = t[p];
    if (c == '{') {
      ++p;
      Json o = Json::object();
      if (eat('}')) return o;
      do {
        std::string k = str();
        if (!eat(':')) fail("expected ':'");
        o[k] = value();
      } while (eat(','));
      if (!eat('}')) fail("expected '}'");
      return o;
    }
    if (c == '[') {
      ++p;
      Json a = Json::array();
      if (eat(']')) return a;
      do a.push_back(value());
      while (eat(','));
      if (!eat(']')) fail("expected ']'");
      return a;
    }
    if (c == '"') return Json(str());
    if (t.compare(p, 4, "true") == 0) return p += 4, Json(true);
    if (t.compare(p, 5, "false") == 0) return p += 5, Json(false);
    if (t.compare(p, 4, "null") == 0) return p += 4, Json();
    char* end = nullptr;
    const double v = std::strtod(t.c_str() + p, &end);
    if (end == t.c_str() + p) fail("unexpected character");
    p = end - t.c_str();
    return Json(v);
  }
};
} // namespace

Json Json::parse(const std::string& text) {
  Parser parser{text};
  Json v = parser.value();
  parser.skip();
  if (parser.p != text.size()) parser.fail("trailing characters");
  return v;
}

} // namespace twinflow::io
