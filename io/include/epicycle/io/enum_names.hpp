// One table of names per enum that is read from or written as a word (a scene key's value, a
// command-line option, a JSON field): the name of a value and the value of a name both read the
// same table, so that the two directions cannot disagree.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace epicycle::io {

/// One value of an enum and its name.
template <class E>
struct EnumName {
  E value;
  const char* name;
};

/// The name of `value` in `table`; nullptr if the table does not hold it.
template <class E, std::size_t N>
constexpr const char* NameOf(const std::array<EnumName<E>, N>& table, E value) {
  for (const EnumName<E>& e : table)
    if (e.value == value) return e.name;
  return nullptr;
}

/// The value named `name` in `table`; empty if no value has that name.
template <class E, std::size_t N>
constexpr std::optional<E> ValueOf(const std::array<EnumName<E>, N>& table, std::string_view name) {
  for (const EnumName<E>& e : table)
    if (name == e.name) return e.value;
  return std::nullopt;
}

/// The names in the table's order (a reader's list of allowed words).
template <class E, std::size_t N>
std::vector<std::string> Names(const std::array<EnumName<E>, N>& table) {
  std::vector<std::string> names;
  for (const EnumName<E>& e : table) names.emplace_back(e.name);
  return names;
}

/// The names joined for a message: "a, b, c" (`last` = ", ") or "a, b or c" (`last` = " or ").
template <class E, std::size_t N>
std::string NameList(const std::array<EnumName<E>, N>& table, std::string_view last = ", ") {
  std::string list;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) list += i + 1 == N ? last : std::string_view(", ");
    list += table[i].name;
  }
  return list;
}

}  // namespace epicycle::io
