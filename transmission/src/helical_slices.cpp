// Helical meshes in slices (helical_slices.hpp; docs/model.md §10).
#include "epicycle/transmission/helical_slices.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "epicycle/geometry/helical.hpp"
#include "epicycle/transmission/record.hpp"
#include "epicycle/transmission/stage_model.hpp"

namespace epicycle::transmission {

namespace {

const geometry::Gear& GearOf(const geometry::Stage& stage, int body) {
  if (body == kSunBody) return stage.sun();
  if (body == kRingBody) return stage.ring();
  return stage.planet(body - PlanetBody(0));
}

// tan β_b = tan β cos α_t of a gear (its spec holds the transverse α_t and the helix).
double TanBaseHelix(const geometry::Gear& g) {
  return std::tan(g.spec().helix.angle) * std::cos(g.spec().pressure_angle);
}

// The poses of the section at z: every gear turned by its lead about its own axis.
void TurnSection(const geometry::Gear& gear, double z, geometry::GearPose* pose) {
  pose->rotation += geometry::SectionTurn(gear, z);
}
void TurnSections(const geometry::Stage& stage, double z, geometry::StagePoses* poses) {
  TurnSection(stage.sun(), z, &poses->sun);
  TurnSection(stage.ring(), z, &poses->ring);
  for (int i = 0; i < stage.planets(); ++i)
    TurnSection(stage.planet(i), z, &poses->planets[static_cast<std::size_t>(i)]);
}
void TurnSections(const geometry::GearPair& pair, double z, geometry::PairPoses* poses) {
  TurnSection(pair.gear1(), z, &poses->gear1);
  TurnSection(pair.gear2(), z, &poses->gear2);
}

double ContactZ(const geometry::Stage& stage, const StageContact& c) {
  const double b = geometry::ContactFaceWidth(GearOf(stage, c.body_a), GearOf(stage, c.body_b));
  return SliceCentre(c.slice, c.slices, b);
}

}  // namespace

bool IsHelicalStage(const geometry::Stage& stage) {
  return stage.sun().spec().helix.helical() || stage.ring().spec().helix.helical() ||
         stage.planet(0).spec().helix.helical();
}

double LocalWidthFactor(const geometry::Gear& a, const geometry::Gear& b) {
  // Both gears of a mesh share β_b (geometry::CheckMeshHelices: the same β and α_t).
  (void)b;
  return std::cos(std::atan(TanBaseHelix(a)));
}

StageOutcome HelicalSliceTerms(const geometry::Stage& stage, const StageCompliance& compliance,
                               const FaceWidthModel& faces, const DamageModel& damage,
                               const geometry::StagePoses& poses, double gap_window,
                               ContactTerms* terms) {
  ContactTerms& t = *terms;
  const int S = faces.slices();
  t.contacts.clear();
  t.local.clear();
  std::vector<StageContact> found;
  // The sun–planet and the planet–ring meshes may differ in width: each slice's z is its mesh's.
  // One search per slice when both meshes have the same width.
  const bool same_width = faces.MeshWidth(false) == faces.MeshWidth(true);
  for (int s = 0; s < S; ++s) {
    for (const bool ring : {false, true}) {
      if (same_width && ring) continue;
      const double z = SliceCentre(s, S, faces.MeshWidth(ring));
      geometry::StagePoses turned = poses;
      TurnSections(stage, z, &turned);
      if (StageOutcome o = SearchStage(stage, turned, gap_window, &found); !o.ok()) return o;
      for (StageContact& c : found) {
        if (!same_width && (c.mesh == geometry::MeshKind::kPlanetRing) != ring) continue;
        c.slice = s;
        c.slices = S;
        c.width_fraction /= S;
        c.section_turn_a = geometry::SectionTurn(GearOf(stage, c.body_a), z);
        c.section_turn_b = geometry::SectionTurn(GearOf(stage, c.body_b), z);
        const double pit = damage.DepthAt(c.body_a, c.body_b, c.contact, (s + 0.5) / S);
        c.pit_depth = pit;
        c.contact.overlap += faces.GapChange(poses, c, s) - pit;
        t.contacts.push_back(c);
      }
    }
  }
  const int n = t.size();
  t.overlap.resize(n);
  for (int j = 0; j < n; ++j) t.overlap(j) = t.contacts[static_cast<std::size_t>(j)].contact.overlap;
  if (n == 0) {
    t.compliance.resize(0, 0);
    return {};
  }
  if (StageOutcome o = compliance.TryMatrix(stage, poses, t.contacts, &t.compliance); !o.ok())
    return o;
  for (int j = 0; j < n; ++j) {
    const StageContact& a = t.contacts[static_cast<std::size_t>(j)];
    for (int k = 0; k < n; ++k) {
      const StageContact& b = t.contacts[static_cast<std::size_t>(k)];
      const bool ring = a.mesh == geometry::MeshKind::kPlanetRing &&
                        b.mesh == geometry::MeshKind::kPlanetRing;
      t.compliance(j, k) *= faces.Coupling(ring)(a.slice, b.slice);
    }
  }
  return {};
}

PairSliceContacts HelicalPairSlices(const geometry::GearPair& pair, const PairFaceWidth& faces,
                                    const geometry::PairPoses& poses,
                                    const geometry::ContactSearchOptions& search) {
  if (!faces.active())
    throw std::invalid_argument("HelicalPairSlices: slices = " + std::to_string(faces.slices()) +
                                ": a helical pair needs slices >= 2");
  PairSliceContacts out;
  const int S = faces.slices();
  for (int s = 0; s < S; ++s) {
    const double z = SliceCentre(s, S, faces.width());
    geometry::PairPoses turned = poses;
    TurnSections(pair, z, &turned);
    const std::array<double, 2> turn{geometry::SectionTurn(pair.gear1(), z),
                                     geometry::SectionTurn(pair.gear2(), z)};
    for (geometry::PotentialContact& c : pair.Contacts(turned, search)) {
      c.overlap += faces.GapChange(c, s);
      out.contacts.push_back(c);
      out.slice.push_back(s);
      out.section_turn.push_back(turn);
    }
  }
  return out;
}

HelicalLoads HelicalLoadsOf(const geometry::Stage& stage, const geometry::StagePoses& poses,
                            const std::vector<StageContact>& contacts,
                            const Eigen::VectorXd& force) {
  HelicalLoads out;
  if (!IsHelicalStage(stage)) return out;
  const int n = stage.planets();
  out.planets.resize(static_cast<std::size_t>(n));
  std::vector<Eigen::Vector3d> axial_moment(static_cast<std::size_t>(n), Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> moment(static_cast<std::size_t>(n), Eigen::Vector3d::Zero());
  for (std::size_t j = 0; j < contacts.size() && j < static_cast<std::size_t>(force.size()); ++j) {
    const StageContact& c = contacts[j];
    const double f = force(static_cast<Eigen::Index>(j));
    if (f == 0) continue;
    const geometry::PotentialContact& p = c.contact;
    const double z = ContactZ(stage, c);
    for (const bool on_a : {true, false}) {
      const int body = on_a ? c.body_a : c.body_b;
      const geometry::Gear& g = GearOf(stage, body);
      const int side = on_a ? p.side_a : p.side_b;
      const double fa = side * g.spec().helix.sign() * f * TanBaseHelix(g);  // along +z
      if (body == kSunBody) out.sun_axial_force += fa;
      if (body == kRingBody) out.ring_axial_force += fa;
      if (body < PlanetBody(0)) continue;
      const int i = body - PlanetBody(0);
      PlanetHelicalLoad& l = out.planets[static_cast<std::size_t>(i)];
      l.axial_force += fa;
      (c.mesh == geometry::MeshKind::kPlanetRing ? l.ring_mesh_axial : l.sun_mesh_axial) += fa;
      const Eigen::Vector2d d = p.point - poses.planets[static_cast<std::size_t>(i)].rotation_centre;
      const Eigen::Vector2d ft = (on_a ? -f : f) * p.normal;  // the transverse force on it
      const Eigen::Vector3d r(d.x(), d.y(), z);
      axial_moment[static_cast<std::size_t>(i)] += r.cross(Eigen::Vector3d(0, 0, fa));
      moment[static_cast<std::size_t>(i)] += r.cross(Eigen::Vector3d(ft.x(), ft.y(), fa));
    }
  }
  for (int i = 0; i < n; ++i) {
    PlanetHelicalLoad& l = out.planets[static_cast<std::size_t>(i)];
    l.planet = i;
    const Eigen::Vector2d c = poses.planets[static_cast<std::size_t>(i)].rotation_centre;
    const Eigen::Vector2d er = c.norm() > 0 ? Eigen::Vector2d(c / c.norm()) : Eigen::Vector2d(1, 0);
    const Eigen::Vector2d et(-er.y(), er.x());
    const Eigen::Vector3d& ma = axial_moment[static_cast<std::size_t>(i)];
    const Eigen::Vector3d& m = moment[static_cast<std::size_t>(i)];
    l.axial_moment_radial = ma.head<2>().dot(er);
    l.axial_moment_tangential = ma.head<2>().dot(et);
    l.moment_radial = m.head<2>().dot(er);
    l.moment_tangential = m.head<2>().dot(et);
    out.carrier_axial_force += l.axial_force;
  }
  return out;
}

void AddHelicalLoads(const HelicalLoads& loads, double w, HelicalLoads* sum) {
  if (sum->planets.empty()) sum->planets.resize(loads.planets.size());
  for (std::size_t i = 0; i < loads.planets.size() && i < sum->planets.size(); ++i) {
    sum->planets[i].planet = loads.planets[i].planet;
    for (const auto& f : kPlanetHelicalFields)
      sum->planets[i].*f.value += w * loads.planets[i].*f.value;
  }
  for (const auto& f : kHelicalMemberFields) sum->*f.value += w * loads.*f.value;
}

void HelicalLoadRange::Add(const HelicalLoads& loads) {
  if (loads.planets.empty()) return;
  AddHelicalLoads(loads, 1.0, &mean);
  if (max_abs.planets.empty()) max_abs.planets.resize(loads.planets.size());
  for (std::size_t i = 0; i < loads.planets.size() && i < max_abs.planets.size(); ++i) {
    max_abs.planets[i].planet = loads.planets[i].planet;
    for (const auto& f : kPlanetHelicalFields)
      max_abs.planets[i].*f.value =
          std::max(max_abs.planets[i].*f.value, std::abs(loads.planets[i].*f.value));
  }
  for (const auto& f : kHelicalMemberFields)
    max_abs.*f.value = std::max(max_abs.*f.value, std::abs(loads.*f.value));
  ++count;
}

void HelicalLoadRange::Finish() {
  if (count == 0) return;
  HelicalLoads sum = std::move(mean);
  mean = {};
  AddHelicalLoads(sum, 1.0 / count, &mean);
}

namespace {

// The `helical` object of `planets`' stage: for every field f of the members and then of each
// planet, value(name(f), f, planet) writes it (planet −1 for the members' fields).
template <typename Name, typename Value>
void VisitHelicalObject(RecordVisitor& visit, const std::vector<PlanetHelicalLoad>& planets,
                        Name&& name, Value&& value) {
  // +z along the gears' axis (helical_slices.hpp).
  visit.BeginObject("helical");
  visit.Text("axial_and_tilting_motion", "held: planar degrees of freedom, pins rigid in tilt");
  for (const auto& f : kHelicalMemberFields) value(name(f), f, -1);
  visit.BeginList("planets");
  for (std::size_t i = 0; i < planets.size(); ++i) {
    visit.Item();
    visit.Integer("planet", planets[i].planet + 1);
    for (const auto& f : kPlanetHelicalFields) value(name(f), f, static_cast<int>(i));
  }
  visit.EndList();
  visit.EndObject();
}

}  // namespace

void VisitHelicalLoads(RecordVisitor& visit, const HelicalLoads& loads) {
  if (loads.planets.empty()) return;
  VisitHelicalObject(
      visit, loads.planets,
      [](const auto& f) { return std::string(f.name) + "_" + f.unit; },
      [&](const std::string& key, const auto& f, int i) {
        if constexpr (std::is_same_v<std::decay_t<decltype(f)>, HelicalField<HelicalLoads>>)
          visit.Number(key.c_str(), loads.*f.value);
        else
          visit.Number(key.c_str(), loads.planets[static_cast<std::size_t>(i)].*f.value);
      });
}

void VisitHelicalLoads(RecordVisitor& visit, const HelicalLoadRange& range) {
  if (range.count == 0) return;
  VisitHelicalObject(
      visit, range.mean.planets, [](const auto& f) { return std::string(f.name); },
      [&](const std::string& key, const auto& f, int i) {
        const std::string unit = std::string("_") + f.unit;
        if constexpr (std::is_same_v<std::decay_t<decltype(f)>, HelicalField<HelicalLoads>>) {
          visit.Number((key + "_mean" + unit).c_str(), range.mean.*f.value);
          visit.Number((key + "_max_abs" + unit).c_str(), range.max_abs.*f.value);
        } else {
          const auto k = static_cast<std::size_t>(i);
          visit.Number((key + "_mean" + unit).c_str(), range.mean.planets[k].*f.value);
          visit.Number((key + "_max_abs" + unit).c_str(), range.max_abs.planets[k].*f.value);
        }
      });
}

}  // namespace epicycle::transmission
