// Binary values of the cache files' payloads (influence_cache.hpp): written and read in this
// machine's byte order, a short read named by the payload it belongs to.
#pragma once

#include <istream>
#include <ostream>
#include <stdexcept>
#include <string>

namespace epicycle::compliance::internal {

template <typename T>
void Put(std::ostream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof(T));
}

/// @throws std::runtime_error "<what> payload truncated" on a short read.
template <typename T>
T Get(std::istream& in, const char* what) {
  T v{};
  in.read(reinterpret_cast<char*>(&v), sizeof(T));
  if (!in) throw std::runtime_error(std::string(what) + " payload truncated");
  return v;
}

}  // namespace epicycle::compliance::internal
