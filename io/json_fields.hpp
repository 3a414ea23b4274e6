#pragma once
// A plain struct as a JSON object, one key per member (its name), for any nlohmann JSON type:
//   TWINFLOW_JSON_FIELDS(SceneParameters, dim, box, ...)
// in the struct's namespace (where nlohmann's serializer looks). A key absent from the object
// reads as the member's default (a record written before the member existed). The member list
// is checked against the struct at compile time: a member left out of it does not compile.
// Enumerations are written as their number (nlohmann's default). The bodies are those of
// nlohmann's NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT, templated on the JSON type: 3.11.2's
// macro serves nlohmann::json only, and io::Json is ordered_json.

#include <cstddef>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>

namespace twinflow::io::detail {

// Converts to any member type: T{AnyMember{}, ...} is well formed while there are no more
// initialisers than members.
struct AnyMember {
  template <class T> operator T() const; // declared only: used in unevaluated contexts
};

template <class T, class... Initialisers>
constexpr auto initialisable(int) -> decltype(T{std::declval<Initialisers>()...}, true) {
  return true;
}
template <class T, class... Initialisers> constexpr bool initialisable(...) {
  return false;
}

// The number of members of the aggregate T (no base classes, no C arrays).
template <class T, class... Initialisers> constexpr std::size_t member_count() {
  if constexpr (initialisable<T, Initialisers..., AnyMember>(0))
    return member_count<T, Initialisers..., AnyMember>();
  else
    return sizeof...(Initialisers);
}

// The number of names in "a, b, c".
constexpr std::size_t name_count(std::string_view names) {
  std::size_t n = 1;
  for (char c : names) n += c == ',';
  return n;
}

} // namespace twinflow::io::detail

#define TWINFLOW_JSON_FIELDS(Type, ...)                                                            \
  static_assert(::twinflow::io::detail::member_count<Type>() ==                                    \
                    ::twinflow::io::detail::name_count(#__VA_ARGS__),                              \
                "TWINFLOW_JSON_FIELDS(" #Type ", ...) must name every member of " #Type);          \
  template <class Json> void to_json(Json& nlohmann_json_j, const Type& nlohmann_json_t) {         \
    NLOHMANN_JSON_EXPAND(NLOHMANN_JSON_PASTE(NLOHMANN_JSON_TO, __VA_ARGS__))                       \
  }                                                                                                \
  template <class Json> void from_json(const Json& nlohmann_json_j, Type& nlohmann_json_t) {       \
    const Type nlohmann_json_default_obj{};                                                        \
    NLOHMANN_JSON_EXPAND(NLOHMANN_JSON_PASTE(NLOHMANN_JSON_FROM_WITH_DEFAULT, __VA_ARGS__))        \
  }
