// Contact pressures and ISO 6336 ratings for a run's summary (docs/stresses.md): JSON with units in
// the names, and the text the commands print.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "epicycle/transmission/contact_pressure.hpp"
#include "epicycle/transmission/rating.hpp"

namespace epicycle::report {

/// Per gear and flank side the largest p_H [MPa], its half-width [µm], the gear's roll angle
/// [deg], tooth, mesh, tip contact or not, the local term's validity ratio, and the state's x
/// ("<x_name>": x times `x_scale`).
nlohmann::json ContactPressureJson(const std::vector<transmission::FlankPressure>& flanks,
                                   const std::string& x_name, double x_scale);
/// The same as text lines ("" without flanks).
std::string ContactPressureText(const std::vector<transmission::FlankPressure>& flanks,
                                const std::string& x_name, double x_scale);

/// Every factor (symbol, value, source) and per gear the ISO columns with the table's and the
/// run's K_γ and the model's own, stresses in MPa; null where a value does not exist.
nlohmann::json RatingJson(const transmission::StageRating& rating);
/// The table the commands print: per gear σ and S for bending and contact, ISO with the table's
/// K_γ, ISO with the run's K_γ, and the model's own; then the factors with their sources.
std::string RatingText(const transmission::StageRating& rating);

}  // namespace epicycle::report
