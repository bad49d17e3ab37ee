// Raising for the parts of a run that did not complete: a speed sweep's speeds, a study's cases.
#pragma once

#include <string>
#include <vector>

#include "common.hpp"

namespace epicycle::python {

/// When a part of `parts` (each with ok() and status) did not complete, raises "F of N `noun`
/// failed `why`" with `result` (RaiseFailures: the ComputationError subclass of their status
/// when they share one, else ComputationError); returns otherwise.
template <class Part>
void RaiseFailedParts(const std::vector<Part>& parts, const std::string& noun,
                      const std::string& why, const py::object& result) {
  std::vector<transmission::RunStatus> failed;
  for (const Part& p : parts)
    if (!p.ok()) failed.push_back(p.status);
  if (!failed.empty())
    RaiseFailures(failed,
                  std::to_string(failed.size()) + " of " + std::to_string(parts.size()) + " " +
                      noun + " failed " + why,
                  result);
}

}  // namespace epicycle::python
