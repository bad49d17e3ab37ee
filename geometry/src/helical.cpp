#include "epicycle/geometry/helical.hpp"

#include <cmath>
#include <stdexcept>

#include "messages.hpp"

namespace epicycle::geometry {

GearSpec TransverseSpec(GearSpec normal) {
  if (!normal.helix.helical()) return normal;
  const TransverseQuantities t = Transverse(normal.teeth, normal.module, normal.pressure_angle,
                                            normal.profile_shift, normal.helix.angle);
  normal.module = t.module;
  normal.pressure_angle = t.pressure_angle;
  normal.profile_shift = t.profile_shift;
  // A helical shaper's transverse section is a spur shaper of the transverse module; its shift
  // is the same radial displacement x_n m_n = x_t m_t.
  if (normal.shaper) normal.shaper->profile_shift *= std::cos(normal.helix.angle);
  return normal;
}

double NormalModule(const Gear& gear) { return gear.module() * std::cos(gear.spec().helix.angle); }

double SectionTurn(const Gear& gear, double z) {
  const Helix& h = gear.spec().helix;
  if (!h.helical()) return 0.0;
  // 2 tan β / d with d = 2 r: the lead p_z = π d / tan β turns the section by 2π.
  return h.sign() * std::tan(h.angle) * z / gear.reference_radius();
}

Vec3 SurfacePoint(const Gear& gear, const Vec2& p, double z) {
  const Vec2 q = Rotate(p, SectionTurn(gear, z));
  return {q.x(), q.y(), z};
}

namespace {

double BaseHelixAngle(const Gear& g) {
  return std::atan(std::tan(g.spec().helix.angle) * std::cos(g.spec().pressure_angle));
}

}  // namespace

HelicalMesh SummariseHelicalMesh(const MeshSummary& m, const Gear& g1, const Gear& g2) {
  HelicalMesh h;
  h.name = m.name;
  h.face_width = ContactFaceWidth(g1, g2);
  h.transverse_module = g1.module();
  h.normal_module = NormalModule(g1);
  h.helix_angle = g1.spec().helix.angle;
  h.base_helix_angle = BaseHelixAngle(g1);
  h.working_pressure_angle = m.pressure_angle;
  h.working_helix_angle = WorkingHelixAngle(h.base_helix_angle, m.pressure_angle);
  h.transverse_contact_ratio = m.contact_ratio_iso;
  h.overlap_ratio = OverlapRatio(h.face_width, h.helix_angle, h.normal_module);
  h.total_contact_ratio = h.transverse_contact_ratio + h.overlap_ratio;
  return h;
}

StageAxialLoads AxialLoads(const Stage& stage, double sun_torque) {
  if (!(sun_torque != 0) || !std::isfinite(sun_torque))
    Fail("load", "sun_torque_Nm", Num(sun_torque), "must be finite and non-zero");
  const int n = stage.planets();
  const double f_bt = std::abs(sun_torque) / (n * stage.sun().base_radius());
  StageAxialLoads out;
  for (int i = 0; i < n; ++i) {
    const Gear& planet = stage.planet(i);
    const int hand = planet.spec().helix.sign();
    const double beta_b = BaseHelixAngle(planet);
    double moment = 0, net = 0;
    for (MeshKind kind : {MeshKind::kSunPlanet, MeshKind::kPlanetRing}) {
      const MeshSummary& m = stage.meshes()[MeshIndex(i, kind)];
      MeshAxialLoad a;
      a.name = m.name;
      a.base_transverse_force = f_bt;
      a.transverse_force = f_bt * std::cos(m.pressure_angle);
      a.axial_force = a.transverse_force * std::tan(WorkingHelixAngle(beta_b, m.pressure_angle));
      // The planet's loaded flank in this mesh (σ), its hand (h): σ h F_a along +z.
      const int side =
          kind == MeshKind::kSunPlanet ? stage.sun_mesh_side() : stage.ring_mesh_planet_side();
      a.axial_on_planet = planet.spec().helix.helical() ? side * hand * a.axial_force : 0.0;
      a.planet_arm = planet.base_radius() / std::cos(m.pressure_angle);
      // The sun mesh's pitch point lies at −r_w e_r from the planet's centre, the ring mesh's at
      // +r_w e_r; (ρ × F_a z) · e_t = −(ρ · e_r) F_a.
      moment += (kind == MeshKind::kSunPlanet ? 1.0 : -1.0) * a.planet_arm * a.axial_on_planet;
      net += a.axial_on_planet;
      (kind == MeshKind::kSunPlanet ? out.sun_axial_force : out.ring_axial_force) -=
          a.axial_on_planet;
      out.meshes.push_back(a);
    }
    out.planets.push_back({i, moment, net});
  }
  return out;
}

void CheckMeshHelices(const GearSpec& g1, const GearSpec& g2, bool internal) {
  if (std::abs(g1.helix.angle - g2.helix.angle) > 1e-12)
    Fail(g2.name, "helix_angle_deg", Num(Deg(g2.helix.angle)),
         "must equal " + g1.name + ".helix_angle_deg = " + Num(Deg(g1.helix.angle)) +
             " (gears that mesh share the helix angle at the reference cylinder)");
  if (!g1.helix.helical()) return;
  const bool same = g1.helix.hand == g2.helix.hand;
  const std::string hand1 = HandName(g1.helix.hand);
  const std::string value = std::string("\"") + HandName(g2.helix.hand) + "\"";
  if (internal && !same)
    Fail(g2.name, "hand", value,
         "must be \"" + hand1 + "\", the hand of the " + g1.name +
             ": an internal mesh needs the same hand on both gears");
  if (!internal && same)
    Fail(g2.name, "hand", value,
         "must be the opposite of the " + g1.name + "'s \"" + hand1 +
             "\": an external mesh needs opposite hands");
}

}  // namespace epicycle::geometry
