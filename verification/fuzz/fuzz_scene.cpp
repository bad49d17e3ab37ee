// libFuzzer target: the scene reader and the stage it describes (tools/fuzz.sh).
#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  epicycle::fuzz::FuzzScene(data, size);
  return 0;
}
