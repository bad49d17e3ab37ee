// How a study knows it was started by an MPI launcher (studies::DetectMpiLaunch, from tables of
// environment variables written here as mpirun, srun and a PMIx launcher set them), and, in a
// build without MPI, that a study started as one of several processes is refused with a message
// that says how to build MPI in.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>

#include "epicycle/config.h"
#include "epicycle/studies/runner.hpp"

using epicycle::studies::DetectMpiLaunch;
using epicycle::studies::MpiLaunch;

namespace {

MpiLaunch Detect(const std::map<std::string, std::string>& env) {
  return DetectMpiLaunch([&](const char* name) -> const char* {
    const auto it = env.find(name);
    return it == env.end() ? nullptr : it->second.c_str();
  });
}

}  // namespace

TEST_CASE("an MPI launch is told by OpenMPI's, PMI's and PMIx's variables",
          "[unit][studies][mpi]") {
  SECTION("no launcher") {
    const MpiLaunch l = Detect({{"HOME", "/root"}});
    CHECK_FALSE(l.launched);
    CHECK_FALSE(l.Parallel());
    CHECK(l.evidence.empty());
  }
  SECTION("mpirun -np 2, second rank") {
    const MpiLaunch l = Detect({{"OMPI_COMM_WORLD_SIZE", "2"}, {"OMPI_COMM_WORLD_RANK", "1"}});
    CHECK(l.launched);
    CHECK(l.size == 2);
    CHECK(l.rank == 1);
    CHECK(l.Parallel());
    CHECK(l.evidence == "OMPI_COMM_WORLD_SIZE = 2, OMPI_COMM_WORLD_RANK = 1");
  }
  SECTION("mpirun -np 1: launched, one process") {
    const MpiLaunch l = Detect({{"OMPI_COMM_WORLD_SIZE", "1"}, {"OMPI_COMM_WORLD_RANK", "0"}});
    CHECK(l.launched);
    CHECK_FALSE(l.Parallel());
  }
  SECTION("srun with PMI, rank 0 of 4") {
    const MpiLaunch l = Detect({{"PMI_SIZE", "4"}, {"PMI_RANK", "0"}});
    CHECK(l.size == 4);
    CHECK(l.rank == 0);
    CHECK(l.Parallel());
  }
  SECTION("PMIx gives a rank only: a rank > 0 is a parallel launch, rank 0 alone is not") {
    CHECK(Detect({{"PMIX_RANK", "3"}}).Parallel());
    const MpiLaunch l = Detect({{"PMIX_RANK", "0"}});
    CHECK(l.launched);
    CHECK_FALSE(l.Parallel());
  }
  SECTION("a value that is not a whole number: launched, size and rank unknown") {
    const MpiLaunch l = Detect({{"PMI_SIZE", "two"}});
    CHECK(l.launched);
    CHECK(l.size == 1);
    CHECK(l.evidence == "PMI_SIZE = two");
  }
}

#if !EPICYCLE_HAVE_MPI
// Only a build without MPI can be asked this in-process: with MPI the session would start MPI.
TEST_CASE("a build without MPI refuses to run as one of several launched processes",
          "[unit][studies][mpi]") {
  ::setenv("OMPI_COMM_WORLD_SIZE", "2", 1);
  ::setenv("OMPI_COMM_WORLD_RANK", "0", 1);
  try {
    const epicycle::studies::MpiSession session;
    FAIL("no refusal");
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    CHECK_THAT(m, Catch::Matchers::Contains("OMPI_COMM_WORLD_SIZE = 2"));
    CHECK_THAT(m, Catch::Matchers::Contains("-DEPICYCLE_WITH_MPI=ON"));
  }
  ::unsetenv("OMPI_COMM_WORLD_SIZE");
  ::unsetenv("OMPI_COMM_WORLD_RANK");
  const epicycle::studies::MpiSession alone;  // no launcher: one process
  CHECK_FALSE(alone.active());
}
#endif
