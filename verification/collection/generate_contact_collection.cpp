// Writes the contact problem collection (verification/data/contact/, docs/solvers.md):
//   generate_contact_collection DIR [SEED]   (default seed 1)
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "contact_collection.hpp"

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: generate_contact_collection DIR [SEED]\n");
    return 2;
  }
  try {
    const std::string dir = argv[1];
    const std::uint64_t seed = argc == 3 ? std::stoull(argv[2]) : 1;
    std::filesystem::create_directories(dir);
    const auto cases = epicycle::solvers::GenerateContactCollection(seed);
    for (const auto& f : cases) {
      epicycle::solvers::WriteContactProblemFile(
          f, (std::filesystem::path(dir) / (f.data.name + ".json")).string());
    }
    std::printf("wrote %zu problem files to %s (seed %llu)\n", cases.size(), dir.c_str(),
                static_cast<unsigned long long>(seed));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "generate_contact_collection: %s\n", e.what());
    return 2;
  }
}
