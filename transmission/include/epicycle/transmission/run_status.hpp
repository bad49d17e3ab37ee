// How a run above the contact level ended: a dynamic run, one speed of a speed sweep, one case of
// a study. A numerical outcome is this status in the run's record, never an exception (bad input
// throws std::invalid_argument before anything is computed; docs/dynamic.md, "Outcomes").
#pragma once

#include <array>

#include "epicycle/io/enum_names.hpp"

namespace epicycle::transmission {

enum class RunStatus {
  kCompleted,          ///< every output reached
  kContactFailure,     ///< a contact solve failed where the run could not step around it
  kIntegratorFailure,  ///< the integrator gave up (error test, Newton iteration, step count)
  kTimeLimit,          ///< the wall-time budget of the run was spent
  kGeometry,           ///< a member swung past where its meshes can be evaluated
  kBadSampledValue,    ///< a study case's sampled input broke a rule of the scene (not run)
};                     // append only

/// The statuses' names in records and messages: the one table of RunStatusName.
inline constexpr std::array<io::EnumName<RunStatus>, 6> kRunStatusNames{{
    {RunStatus::kCompleted, "completed"},
    {RunStatus::kContactFailure, "contact-failure"},
    {RunStatus::kIntegratorFailure, "integrator-failure"},
    {RunStatus::kTimeLimit, "time-limit"},
    {RunStatus::kGeometry, "geometry"},
    {RunStatus::kBadSampledValue, "bad-sampled-value"},
}};

inline const char* RunStatusName(RunStatus status) { return io::NameOf(kRunStatusNames, status); }

}  // namespace epicycle::transmission
