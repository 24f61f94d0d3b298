// An enumeration's values by the names the files and messages give them,
// declared once beside the enumeration (a table of schema::Name) and read by
// the file formats' Choice fields (hb/json_schema.h) and by the code that
// prints them, so that a name is never spelt twice.
#pragma once

#include <cstddef>
#include <string_view>

namespace beamid::schema {

// An enumeration written by name.
template <typename E>
struct Name {
  E value;
  std::string_view name;
};

// The name of an enumeration's value, as a Choice writes it ("" when the
// list has none).
template <typename E, std::size_t N>
constexpr std::string_view NameOf(E value, const Name<E> (&names)[N]) {
  for (const Name<E>& n : names)
    if (n.value == value) return n.name;
  return {};
}

}  // namespace beamid::schema
