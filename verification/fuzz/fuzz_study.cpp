// libFuzzer target: the study-file reader and the sampling of its cases (tools/fuzz.sh).
#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  epicycle::fuzz::FuzzStudy(data, size);
  return 0;
}
