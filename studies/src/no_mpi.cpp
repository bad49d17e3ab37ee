// The MPI entry points of a build without EPICYCLE_WITH_MPI: one process, rank 0 of 1.
#include <stdexcept>
#include <string>

#include "epicycle/config.h"
#include "epicycle/studies/runner.hpp"

#if !EPICYCLE_HAVE_MPI
namespace epicycle::studies {

bool HaveMpi() { return false; }

MpiSession::MpiSession() {
  const MpiLaunch launch = DetectMpiLaunch();
  if (launch.Parallel())
    throw std::invalid_argument(
        "started by an MPI launcher as one of several processes (" + launch.evidence +
        "), but this epicycle was built without MPI: every process would run the whole study "
        "into the same rows file. Build it with MPI (cmake -DEPICYCLE_WITH_MPI=ON, as "
        "tools/setup.sh does), or run it without mpirun/srun (one process, --threads N)");
}
MpiSession::~MpiSession() = default;

RunReport RunStudyMpi(const StudySpec& study, const RunOptions& options) {
  return RunStudy(study, options);
}

}  // namespace epicycle::studies
#endif
