// The geometry report (`epicycle geometry`) and the potential contacts (`epicycle contacts`) as
// console text: the report's JSON (geometry_json.hpp) in tables, the contacts' points, normals,
// overlaps, arms and curvature radii in millimetres.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"

namespace epicycle::report {

/// The report of report::StageJson or PairJson as tables: the gears, the meshes, the fits, the
/// assembly of a stage and the helical section of a helical scene.
std::string GeometryReportText(const nlohmann::json& report);
/// Every potential contact of the stage at carrier angle `carrier_deg` [deg] within the gap
/// window `window` [m], one line each.
std::string StageContactsText(const geometry::Stage& stage, double carrier_deg, double window);
/// The same for a gear pair with gear 1 turned by `angle_deg` [deg].
std::string PairContactsText(const geometry::GearPair& pair, double angle_deg, double window);

}  // namespace epicycle::report
