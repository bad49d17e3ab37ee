// A planet's pin as a load-dependent tilt (pin.hpp; docs/model.md §10, "The planet's pin").
#include "epicycle/transmission/pin.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "epicycle/io/number_format.hpp"
#include "epicycle/transmission/face_width.hpp"
#include "epicycle/transmission/helical_slices.hpp"
#include "epicycle/transmission/stage_problem.hpp"

namespace epicycle::transmission {

double PinBendingStiffness(double youngs_modulus, double diameter, double bore) {
  const double d2 = diameter * diameter, b2 = bore * bore;
  return youngs_modulus * std::numbers::pi * (d2 * d2 - b2 * b2) / 64.0;
}

PinCompliance PinCompliances(const PinSpec& pin) {
  PinCompliance c;
  auto positive = [&](const char* key, double v, const char* unit) {
    if (!(v > 0) || !std::isfinite(v))
      throw std::invalid_argument(pin.where + "." + key + " = " + io::Num(v) + " " + unit +
                                  ": must be finite and > 0");
  };
  if (pin.mounting == PinMounting::kStiffness) {
    if (!(pin.tilting_stiffness > 0))
      throw std::invalid_argument(pin.where + ".tilting_stiffness = " +
                                  io::Num(pin.tilting_stiffness) + " N·m/rad: must be > 0");
    c.moment = std::isinf(pin.tilting_stiffness) ? 0.0 : 1.0 / pin.tilting_stiffness;
    return c;
  }
  positive("diameter", pin.diameter, "m");
  positive("length", pin.length, "m");
  positive("youngs_modulus", pin.youngs_modulus, "Pa");
  if (!(pin.bore >= 0 && pin.bore < pin.diameter))
    throw std::invalid_argument(pin.where + ".bore = " + io::Num(pin.bore) +
                                " m: must be >= 0 and below the diameter " +
                                io::Num(pin.diameter) + " m");
  const double ei = PinBendingStiffness(pin.youngs_modulus, pin.diameter, pin.bore);
  if (pin.mounting == PinMounting::kStraddle) {
    c.moment = pin.length / (16.0 * ei);
  } else {
    c.moment = pin.length / ei;
    c.force = pin.length * pin.length / (2.0 * ei);
    c.side = -pin.clamped_side;
  }
  return c;
}

std::vector<PinLoad> PinLoadsOf(const geometry::Stage& stage, const geometry::StagePoses& poses,
                                const std::vector<StageContact>& contacts,
                                const Eigen::VectorXd& force) {
  const int n = stage.planets();
  std::vector<PinLoad> out(static_cast<std::size_t>(n));
  const double b_sp = geometry::ContactFaceWidth(stage.sun(), stage.planet(0));
  const double b_pr = geometry::ContactFaceWidth(stage.planet(0), stage.ring());
  for (std::size_t j = 0; j < contacts.size() && j < static_cast<std::size_t>(force.size()); ++j) {
    const StageContact& c = contacts[j];
    const double f = force(static_cast<Eigen::Index>(j));
    if (f == 0) continue;
    const bool on_a = c.body_a >= PlanetBody(0);
    const int body = on_a ? c.body_a : c.body_b;
    if (body < PlanetBody(0)) continue;
    const std::size_t i = static_cast<std::size_t>(body - PlanetBody(0));
    const double z =
        c.slices > 1
            ? SliceCentre(c.slice, c.slices, c.mesh == geometry::MeshKind::kPlanetRing ? b_pr : b_sp)
            : 0.0;
    const Eigen::Vector2d ft = (on_a ? -f : f) * c.contact.normal;  // on the planet
    out[i].force += ft;
    // (d, z) × (F_t, 0): the in-plane part is z ẑ × F_t = z (−F_y, F_x).
    out[i].moment += z * Eigen::Vector2d(-ft.y(), ft.x());
  }
  if (IsHelicalStage(stage)) {
    const HelicalLoads h = HelicalLoadsOf(stage, poses, contacts, force);
    for (int i = 0; i < n; ++i) {
      const PlanetHelicalLoad& l = h.planets[static_cast<std::size_t>(i)];
      const Eigen::Vector2d c = poses.planets[static_cast<std::size_t>(i)].rotation_centre;
      const Eigen::Vector2d er = c.norm() > 0 ? Eigen::Vector2d(c / c.norm()) : Eigen::Vector2d(1, 0);
      const Eigen::Vector2d et(-er.y(), er.x());
      out[static_cast<std::size_t>(i)].moment +=
          l.axial_moment_radial * er + l.axial_moment_tangential * et;
    }
  }
  return out;
}

PinModel::PinModel(const std::vector<PinSpec>& pins, int planets) {
  pins_.assign(static_cast<std::size_t>(planets), PinCompliance{});
  // Every planet's entry (planet −1) first, then each planet's own.
  for (const bool own : {false, true})
    for (const PinSpec& p : pins) {
      if ((p.planet >= 0) != own) continue;
      if (p.planet >= planets)
        throw std::invalid_argument(p.where + ".planet = " + std::to_string(p.planet + 1) +
                                    ": the stage has planets 1.." + std::to_string(planets));
      const PinCompliance c = PinCompliances(p);
      for (int i = 0; i < planets; ++i)
        if (p.planet < 0 || p.planet == i) pins_[static_cast<std::size_t>(i)] = c;
    }
  for (const PinCompliance& c : pins_) active_ = active_ || !c.rigid();
}

Eigen::Vector2d PinModel::Tilt(int planet, const PinLoad& load) const {
  const PinCompliance& c = compliance(planet);
  return c.moment * Eigen::Vector2d(load.moment.y(), -load.moment.x()) + c.force * c.side * load.force;
}

}  // namespace epicycle::transmission
