// A value given as fields between separators ("FROM:TO:N", "I:J", "K/N"): the fields as typed and
// each read whole as a number, the way every front end reads such a value, so that "12x" is none.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace epicycle::io {

/// The fields of `spec` between its `separator`s ("500:12000:24": "500", "12000", "24").
inline std::vector<std::string> Fields(const std::string& spec, char separator) {
  std::vector<std::string> fields;
  std::size_t at = 0;
  for (std::size_t c; (c = spec.find(separator, at)) != std::string::npos; at = c + 1)
    fields.push_back(spec.substr(at, c - at));
  fields.push_back(spec.substr(at));
  return fields;
}

/// `field` read whole as a real number (std::stod) or a whole one (std::stol).
/// @throws std::logic_error (invalid_argument, out_of_range) if it is none; the caller names the
///         value and its rule.
inline double Real(const std::string& field) {
  std::size_t used = 0;
  const double value = std::stod(field, &used);
  if (used != field.size()) throw std::invalid_argument(field);
  return value;
}
inline long Whole(const std::string& field) {
  std::size_t used = 0;
  const long value = std::stol(field, &used);
  if (used != field.size()) throw std::invalid_argument(field);
  return value;
}

}  // namespace epicycle::io
