// The transmission error's ripple of a helical stage against its overlap ratio (docs/model.md
// §10, "Helical meshes in slices"; docs/face_width.md, "Helical meshes"): a spur stage's
// transverse section given a helix, swept over one mesh cycle quasi-statically.
#pragma once

#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/stage_model.hpp"

namespace epicycle::transmission {

/// The stage spec `transverse` (transverse modules, pressure angles and shifts) with the helix
/// angle β [rad] on every gear: the sun of hand `sun_hand`, the planets and the ring of the
/// other (an external mesh has opposite hands, an internal one the same). Its transverse
/// sections, and so its FE bodies, are those of `transverse`.
geometry::StageSpec WithHelix(geometry::StageSpec transverse, double helix_angle,
                              geometry::Hand sun_hand);

/// Overlap ratio ε_β = b tan β/(π m_t) [-] of the sun–planet mesh of `stage` (= b sin β/(π m_n)).
double StageOverlapRatio(const geometry::Stage& stage);

/// The loaded static transmission error's peak to peak [rad] over one mesh cycle (2π/z_r of
/// carrier rotation) sampled at `positions` carrier angles, of the model's stage under `loads`
/// (quasi-static, back end default). Positions that do not converge are left out.
/// @throws std::invalid_argument for positions < 2 or no converged position.
double TransmissionErrorRipple(const StageModel& model, const StageLoads& loads, int positions);

}  // namespace epicycle::transmission
