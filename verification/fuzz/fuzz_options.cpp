// libFuzzer target: the program's command line, parsed without running a command (tools/fuzz.sh).
#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  epicycle::fuzz::FuzzOptions(data, size);
  return 0;
}
