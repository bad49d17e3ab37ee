// libFuzzer target: the contact-problem reader and the active-set Newton solve (tools/fuzz.sh).
#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  epicycle::fuzz::FuzzContactProblem(data, size);
  return 0;
}
