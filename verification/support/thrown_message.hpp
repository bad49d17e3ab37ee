// The message of the exception a callable throws, for the checks that bad input is named.
#pragma once

#include <exception>
#include <string>

namespace epicycle::test {

template <class F>
std::string ThrownMessage(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

}  // namespace epicycle::test
