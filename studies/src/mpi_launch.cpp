// What an MPI launcher tells the processes it starts (both builds: with MPI it decides whether to
// start MPI, without it whether to refuse).
#include <charconv>
#include <cstdlib>
#include <cstring>

#include "epicycle/studies/runner.hpp"

namespace epicycle::studies {

MpiLaunch DetectMpiLaunch(const std::function<const char*(const char*)>& lookup) {
  MpiLaunch launch;
  struct EnvVariable {
    const char* name;
    bool size;  // a size, else a rank
  };
  for (const EnvVariable v :
       {EnvVariable{"OMPI_COMM_WORLD_SIZE", true}, EnvVariable{"OMPI_COMM_WORLD_RANK", false},
        EnvVariable{"PMI_SIZE", true}, EnvVariable{"PMI_RANK", false},
        EnvVariable{"PMIX_RANK", false}}) {
    const char* text = lookup(v.name);
    if (text == nullptr) continue;
    launch.launched = true;
    if (!launch.evidence.empty()) launch.evidence += ", ";
    launch.evidence += std::string(v.name) + " = " + text;
    long value = 0;
    const char* end = text + std::strlen(text);
    const auto [stop, error] = std::from_chars(text, end, value);
    if (error != std::errc() || stop != end) continue;
    if (v.size && value > launch.size) launch.size = value;
    if (!v.size && value > launch.rank) launch.rank = value;
  }
  return launch;
}

MpiLaunch DetectMpiLaunch() {
  return DetectMpiLaunch([](const char* name) -> const char* { return std::getenv(name); });
}

}  // namespace epicycle::studies
