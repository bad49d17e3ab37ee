// A speed sweep's console text and summary JSON (docs/speed_sweeps.md): the plan before the
// speeds run, the table of the speeds after, and the record's fields as JSON.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "epicycle/dynamics/speed_sweep_run.hpp"

namespace epicycle::report {

/// The sweep's header: scene, speeds, support and threads, the tables' messages, the secant and
/// tangent mesh stiffnesses, then the modes with their damping, the coincidences and what each
/// speed runs.
std::string SpeedSweepPlanText(const dynamics::SpeedSweepStart& start);

/// The speeds' table (K_γ, K_v and its mesh, TE amplitude, orbit, CPU, status) and the wall and
/// CPU times.
std::string SpeedSweepRecordText(const dynamics::SpeedSweepRecord& record);

/// The summary JSON (SummaryJson): the record's fields (dynamics::VisitRecord) and the program's
/// provenance.
nlohmann::json SpeedSweepRecordJson(const dynamics::SpeedSweepRecord& record,
                                    const nlohmann::json& provenance);

}  // namespace epicycle::report
