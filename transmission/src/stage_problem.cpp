#include "epicycle/transmission/stage_problem.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace epicycle::transmission {

std::string BodyName(int body) {
  return body == kSunBody    ? "sun"
         : body == kRingBody ? "ring"
                             : "planet" + std::to_string(body - PlanetBody(0) + 1);
}

std::vector<std::string> BodyNames(int bodies) {
  std::vector<std::string> names;
  for (int b = 0; b < bodies; ++b) names.push_back(BodyName(b));
  return names;
}

std::vector<compliance::FilletStress> StageCompliance::FilletStresses(
    const geometry::Stage&, const geometry::StagePoses&, const std::vector<StageContact>&,
    const Eigen::VectorXd&, const TangentialLoads*) const {
  throw std::logic_error("this stage compliance has no root-stress model");
}

using geometry::MeshKind;
using geometry::PotentialContact;
using geometry::Vec2;

std::string StageContact::Label() const {
  return geometry::MeshName(planet, mesh) + " " + geometry::KindName(contact.kind) + " " +
         (loaded ? "drive" : "coast") + " teeth " + std::to_string(contact.tooth_a) + "/" +
         std::to_string(contact.tooth_b) +
         (pit_depth > 0 ? " pitted " + std::to_string(part) : std::string()) +
         (slices > 1 ? " slice " + std::to_string(slice + 1) + "/" + std::to_string(slices)
                     : std::string());
}

std::string StageContact::FlankName() const {
  return std::string(loaded ? "drive" : "coast") +
         (pit_depth > 0 ? " pitted " + std::to_string(part) : std::string()) +
         (slices > 1 ? " slice " + std::to_string(slice + 1) + "/" + std::to_string(slices)
                     : std::string());
}

std::string StageDof::Label() const {
  switch (kind) {
    case kSunRotation:
      return "sun rotation [rad]";
    case kSunX:
      return "sun x [m]";
    case kSunY:
      return "sun y [m]";
    case kPlanetRotation:
      return "planet" + std::to_string(planet + 1) + " rotation [rad]";
    case kPlanetX:
      return "planet" + std::to_string(planet + 1) + " x [m]";
    case kPlanetY:
      return "planet" + std::to_string(planet + 1) + " y [m]";
    case kRingRotation:
      return "ring rotation [rad]";
    case kRingX:
      return "ring x [m]";
    case kRingY:
      return "ring y [m]";
  }
  return "?";
}

std::string StatusName(StageStatus status) {
  switch (status) {
    case StageStatus::kOk:
      return "ok";
    case StageStatus::kNoLineOfAction:
      return "no line of action";
    case StageStatus::kOffFlankGrid:
      return "off the flank grid";
    case StageStatus::kNoReducedRadius:
      return "no reduced radius";
    case StageStatus::kNoContact:
      return "no contact";
    case StageStatus::kContactSolveFailed:
      return "contact solve failed";
    case StageStatus::kNotSettled:
      return "not settled";
    case StageStatus::kFrictionNotSettled:
      return "friction not settled";
    case StageStatus::kTiltNotSettled:
      return "tilt not settled";
  }
  return "unknown";
}

std::vector<StageContact> SearchStage(const geometry::Stage& stage,
                                      const geometry::StagePoses& poses, double gap_window) {
  std::vector<StageContact> out;
  const StageOutcome o = SearchStage(stage, poses, gap_window, &out);
  if (!o.ok()) throw std::runtime_error(o.message);
  return out;
}

StageOutcome SearchStage(const geometry::Stage& stage, const geometry::StagePoses& poses,
                         double gap_window, std::vector<StageContact>* contacts,
                         std::vector<geometry::TipRoundReuse>* reuse) {
  if (reuse != nullptr && reuse->size() != static_cast<std::size_t>(2 * stage.planets()))
    reuse->resize(static_cast<std::size_t>(2 * stage.planets()));
  std::vector<StageContact>& out = *contacts;
  out.clear();
  out.reserve(8 * stage.planets());  // a few per mesh and flank side: one allocation
  geometry::ContactSearchOptions opt;
  opt.gap_window = gap_window;
  // One mesh's at a time, in a buffer kept per thread: no allocation once it has grown (the
  // search is on the dynamic model's hot path; the stage and the studies' threads share it).
  thread_local std::vector<PotentialContact> found;
  for (int i = 0; i < stage.planets(); ++i) {
    for (MeshKind kind : {MeshKind::kSunPlanet, MeshKind::kPlanetRing}) {
      const int loaded_side =
          kind == MeshKind::kSunPlanet ? stage.sun_mesh_side() : stage.ring_mesh_planet_side();
      if (!stage.HasLineOfAction(poses, i, kind)) {
        const std::string planet = std::to_string(i + 1);
        return {StageStatus::kNoLineOfAction,
                (kind == MeshKind::kSunPlanet ? "mesh sun-planet" + planet
                                              : "mesh planet" + planet + "-ring") +
                    ": the centres are placed so that the base circles admit no line of action "
                    "(a planet or the sun moved far from its place)"};
      }
      found.clear();
      stage.AppendContacts(poses, i, kind, opt, &found,
                           reuse != nullptr
                               ? &(*reuse)[static_cast<std::size_t>(geometry::MeshIndex(i, kind))]
                               : nullptr);
      for (const PotentialContact& c : found) {
        StageContact s;
        s.contact = c;
        s.planet = i;
        s.mesh = kind;
        s.body_a = kind == MeshKind::kSunPlanet ? kSunBody : PlanetBody(i);
        s.body_b = kind == MeshKind::kSunPlanet ? PlanetBody(i) : kRingBody;
        s.loaded = c.side_a == loaded_side;
        out.push_back(s);
      }
    }
  }
  return {};
}

int CarryForces(const std::vector<StageContact>& from, const Eigen::VectorXd& force,
                const std::vector<StageContact>& to, Eigen::VectorXd* out) {
  if (force.size() != static_cast<Eigen::Index>(from.size()))
    throw std::invalid_argument("CarryForces: " + std::to_string(force.size()) + " forces for " +
                                std::to_string(from.size()) + " contacts");
  const int n = static_cast<int>(to.size());
  *out = Eigen::VectorXd::Zero(n);
  int matched = 0;
  // Both lists are in search order, so contact j's match is mostly the one after contact j − 1's:
  // each scan starts there and wraps around (O(N) for lists that differ by a few contacts, where
  // a scan from the start is O(N²): 240 contacts for 20 face-width slices). A search yields each
  // potential contact once (what SameAs compares names it), so the match found is the only one.
  const std::size_t m = from.size();
  std::size_t next = 0;
  for (int j = 0; j < n; ++j) {
    const StageContact& c = to[static_cast<std::size_t>(j)];
    for (std::size_t step = 0; step < m; ++step) {
      const std::size_t i = next + step < m ? next + step : next + step - m;
      if (from[i].SameAs(c)) {
        (*out)(j) = force(static_cast<Eigen::Index>(i));
        ++matched;
        next = i + 1 < m ? i + 1 : 0;
        break;
      }
    }
  }
  return matched;
}

namespace {

// False if the radii give no positive reduced radius (the caller names the contact).
bool LocalTermOf(const PotentialContact& contact, const geometry::Gear& a, const geometry::Gear& b,
                 const Material& material, solvers::PlaneAssumption plane, double depth_a,
                 double depth_b, solvers::LocalTermParameters* out) {
  solvers::LocalTermParameters& l = *out;
  l.face_width = geometry::ContactFaceWidth(a, b);
  l.plane = plane;
  l.body[0] = {material.youngs_modulus, material.poisson_ratio, depth_a};
  l.body[1] = {material.youngs_modulus, material.poisson_ratio, depth_b};
  const double curvature = 1.0 / contact.curvature_radius_a + 1.0 / contact.curvature_radius_b;
  if (!(curvature > 0) || !std::isfinite(curvature)) return false;
  l.reduced_radius = 1.0 / curvature;
  return true;
}

StageOutcome NoReducedRadius(const PotentialContact& contact, const std::string& label) {
  return {StageStatus::kNoReducedRadius,
          "contact " + label + ": curvature radii " + std::to_string(contact.curvature_radius_a) +
              " m and " + std::to_string(contact.curvature_radius_b) +
              " m give no positive reduced radius"};
}

}  // namespace

StageOutcome ContactLocalTerm(const geometry::PotentialContact& contact, const geometry::Gear& a,
                              const geometry::Gear& b, const Material& material,
                              solvers::PlaneAssumption plane, double depth_a, double depth_b,
                              const std::string& label, solvers::LocalTermParameters* out) {
  if (LocalTermOf(contact, a, b, material, plane, depth_a, depth_b, out)) return {};
  return NoReducedRadius(contact, label);
}

StageOutcome ContactLocalTerm(const StageContact& contact, const geometry::Gear& a,
                              const geometry::Gear& b, const Material& material,
                              solvers::PlaneAssumption plane, double depth_a, double depth_b,
                              solvers::LocalTermParameters* out) {
  if (LocalTermOf(contact.contact, a, b, material, plane, depth_a, depth_b, out)) {
    out->face_width *= contact.width_fraction;  // × 1 exactly for a whole contact
    return {};
  }
  return NoReducedRadius(contact.contact, contact.Label());
}

}  // namespace epicycle::transmission
