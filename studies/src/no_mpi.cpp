// The MPI entry points of a build without EPICYCLE_WITH_MPI: one process, rank 0 of 1.
#include "epicycle/config.h"
#include "epicycle/studies/runner.hpp"

#if !EPICYCLE_HAVE_MPI
namespace epicycle::studies {

bool HaveMpi() { return false; }

MpiSession::MpiSession() = default;
MpiSession::~MpiSession() = default;

RunReport RunStudyMpi(const StudySpec& study, const RunOptions& options) {
  return RunStudy(study, options);
}

}  // namespace epicycle::studies
#endif
