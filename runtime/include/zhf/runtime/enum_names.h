// One table of names per enumeration, from which its names, the parsing of a name and the list of
// names an option or a file field accepts all come: a name is spelled once. Standard library only.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace zhf::runtime {

template <class E>
struct EnumName {
  E value;
  const char* name;
};

// The name of value in table, or "?" for a value the table lacks.
template <class E, std::size_t N>
constexpr const char* enum_name(const EnumName<E> (&table)[N], E value) {
  for (const EnumName<E>& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

// The value called name; false, value untouched, for a name the table lacks.
template <class E, std::size_t N>
bool parse_enum(const EnumName<E> (&table)[N], std::string_view name, E& value) {
  for (const EnumName<E>& entry : table)
    if (name == entry.name) {
      value = entry.value;
      return true;
    }
  return false;
}

// Every name of the table in its order, after the names in first (a choice such as "auto").
template <class E, std::size_t N>
std::vector<std::string> enum_names(const EnumName<E> (&table)[N], std::initializer_list<const char*> first = {}) {
  std::vector<std::string> names(first.begin(), first.end());
  for (const EnumName<E>& entry : table) names.push_back(entry.name);
  return names;
}

// "a, b or c": names for a help text or a message.
inline std::string name_list(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return out;
}

}  // namespace zhf::runtime
