#include "epicycle/transmission/face_width.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "epicycle/io/number_format.hpp"
#include "epicycle/transmission/stage_model.hpp"
#include "epicycle/transmission/stage_problem.hpp"

namespace epicycle::transmission {

namespace {

// sinh(u) sinh(v) / sinh(B) for u, v ≥ 0, u + v ≤ B, without overflow (every exponent ≤ 0).
double SinhSinhOverSinh(double u, double v, double B) {
  return (std::exp(u + v - B) - std::exp(u - v - B) - std::exp(v - u - B) +
          std::exp(-u - v - B)) /
         (2.0 * (1.0 - std::exp(-2.0 * B)));
}

// cosh(w) / sinh(B) for |w| ≤ B, without overflow.
double CoshOverSinh(double w, double B) {
  return (std::exp(w - B) + std::exp(-w - B)) / (1.0 - std::exp(-2.0 * B));
}

// ∫_s ∫_t G(x, x') dx dx' of the Pasternak Green's function on [0, B] with λ = 1 (lengths in
// units of λ; docs/model.md §10), slices s = [a1, a2] and t = [c1, c2] with a2 ≤ c1 or s = t.
// Apart (x < x'): G = cosh x cosh(B − x')/sinh B, so the integral is
//   (sinh a2 − sinh a1)(sinh(B − c1) − sinh(B − c2))/sinh B.
// The same slice [p, q]: twice the integral over x < x',
//   2/sinh B ∫_p^q cosh(B − x') (sinh x' − sinh p) dx'
//   = (q − p) + (cosh(2q − B) − cosh(2p − B))/(2 sinh B)
//     − 2 sinh p (sinh(B − p) − sinh(B − q))/sinh B.
double GreenDoubleIntegral(double a1, double a2, double c1, double c2, double B) {
  if (a1 == c1) {
    const double p = a1, q = a2;
    return (q - p) + 0.5 * (CoshOverSinh(2 * q - B, B) - CoshOverSinh(2 * p - B, B)) -
           2 * (SinhSinhOverSinh(p, B - p, B) - SinhSinhOverSinh(p, B - q, B));
  }
  return SinhSinhOverSinh(a2, B - c1, B) - SinhSinhOverSinh(a2, B - c2, B) -
         SinhSinhOverSinh(a1, B - c1, B) + SinhSinhOverSinh(a1, B - c2, B);
}

}  // namespace

std::vector<double> SliceCentres(int slices, double width) {
  std::vector<double> z(static_cast<std::size_t>(slices));
  for (int s = 0; s < slices; ++s) z[static_cast<std::size_t>(s)] = SliceCentre(s, slices, width);
  return z;
}

Eigen::MatrixXd FaceCouplingMatrix(int slices, double width, FaceCoupling coupling,
                                   double coupling_length, double body_share) {
  if (slices < 1)
    throw std::invalid_argument("face width: slices = " + std::to_string(slices) +
                                ": must be at least 1");
  if (!(width > 0) || !std::isfinite(width))
    throw std::invalid_argument("face width: width = " + io::Num(width) + " m: must be > 0");
  const int n = slices;
  if (coupling == FaceCoupling::kTable)
    throw std::invalid_argument(
        "face width: coupling = table: the kernel is the scene's coupling_table, not computed");
  if (coupling == FaceCoupling::kNone || n == 1)
    return Eigen::MatrixXd::Identity(n, n) * static_cast<double>(n);
  if (coupling == FaceCoupling::kToothBody) {
    if (!(body_share >= 0 && body_share < 1))
      throw std::invalid_argument("face width: body_share = " + io::Num(body_share) +
                                  ": must be in [0, 1) for the tooth_body coupling");
    if (!(coupling_length >= 0) || !std::isfinite(coupling_length))
      throw std::invalid_argument("face width: coupling_length = " + io::Num(coupling_length) +
                                  " m: must be >= 0 for the tooth_body coupling (0: strips)");
    // Rows sum to (1 − φ) S + φ S = S; the tooth part positive definite, the body's semidefinite.
    const Eigen::MatrixXd tooth =
        coupling_length > 0
            ? FaceCouplingMatrix(n, width, FaceCoupling::kPasternak, coupling_length)
            : Eigen::MatrixXd(Eigen::MatrixXd::Identity(n, n) * static_cast<double>(n));
    return (1 - body_share) * tooth + Eigen::MatrixXd::Constant(n, n, body_share);
  }
  if (!(coupling_length > 0) || !std::isfinite(coupling_length))
    throw std::invalid_argument("face width: coupling_length = " + io::Num(coupling_length) +
                                " m: must be > 0 for the Pasternak coupling");
  // In units of λ: the face [0, B], slices of width D; W_st = (S/D) ∫_s ∫_t G.
  const double B = width / coupling_length, D = B / n;
  Eigen::MatrixXd w(n, n);
  for (int s = 0; s < n; ++s)
    for (int t = s; t < n; ++t)
      w(s, t) = w(t, s) = n / D * GreenDoubleIntegral(s * D, (s + 1) * D, t * D, (t + 1) * D, B);
  return w;
}

double LeadRemoved(double crowning, double end_relief, double end_relief_length, double width,
                   double z) {
  double c = 0;
  if (crowning > 0) c += crowning * (2 * z / width) * (2 * z / width);
  if (end_relief > 0) {
    const double into = std::abs(z) - (0.5 * width - end_relief_length);
    if (into > 0) c += end_relief * into / end_relief_length;
  }
  return c;
}

double FaceWidthModel::BodyLead::Removed(double z) const {
  return LeadRemoved(crowning, end_relief, end_relief_length, width, z);
}

FaceWidthModel::FaceWidthModel(const FaceWidthSpec& spec, const geometry::Stage& stage,
                               double carrier_torque)
    : spec_(spec) {
  if (!spec_.active()) return;
  const int planets = stage.planets();
  const int bodies = PlanetBody(planets);
  const std::vector<std::string> names = BodyNames(bodies);
  auto gear_of = [&](int body) -> const geometry::Gear& {
    if (body == kSunBody) return stage.sun();
    if (body == kRingBody) return stage.ring();
    return stage.planet(body - 2);
  };
  lead_.assign(static_cast<std::size_t>(bodies), BodyLead{});
  for (int b = 0; b < bodies; ++b) lead_[b].width = gear_of(b).spec().face_width;
  for (const LeadSpec& l : spec_.leads) {
    const auto it = std::find(names.begin(), names.end(), l.gear);
    if (it == names.end())
      throw std::invalid_argument(l.where + ".gear = \"" + l.gear +
                                  "\": the stage has no such gear");
    BodyLead& b = lead_[static_cast<std::size_t>(it - names.begin())];
    const geometry::Gear& g = gear_of(static_cast<int>(it - names.begin()));
    b.slope = l.slope / (b.width * g.base_radius());
    b.crowning = l.crowning;
    b.end_relief = l.end_relief;
    b.end_relief_length = l.end_relief_length;
  }
  planet_slope_.assign(static_cast<std::size_t>(planets), Eigen::Vector2d::Zero());
  for (const PinTilt& t : spec_.pin_tilts) {
    if (t.planet < 0 || t.planet >= planets)
      throw std::invalid_argument(t.where + ".planet = " + std::to_string(t.planet + 1) +
                                  ": the stage has planets 1.." + std::to_string(planets));
    planet_slope_[static_cast<std::size_t>(t.planet)] += Eigen::Vector2d(t.radial, t.tangential);
  }
  if (spec_.carrier_torsional_stiffness > 0) {
    // The plates twist by Δφ = T_c/k_θ; a pin at the carrier radius r_c spans L between them. The
    // planets drive the carrier in the sense of −T_c (T_c the carrier's external torque, which
    // balances them): the end away from the output plate leads in that sense.
    const double twist = -carrier_torque / spec_.carrier_torsional_stiffness;
    wind_up_slope_ = -spec_.carrier_output_side * twist * stage.carrier_radius() /
                     spec_.carrier_plate_distance;
  }
  pins_ = PinModel(spec_.pins, planets);
  const double b_sp = geometry::ContactFaceWidth(stage.sun(), stage.planet(0));
  const double b_pr = geometry::ContactFaceWidth(stage.planet(0), stage.ring());
  sun_planet_width_ = b_sp;
  planet_ring_width_ = b_pr;
  if (spec_.coupling == FaceCoupling::kTable) {  // each mesh kind's structure (the scene's)
    for (const Eigen::MatrixXd* w : {&spec_.coupling_table, &spec_.coupling_table_planet_ring})
      if (w->rows() != spec_.slices || w->cols() != spec_.slices)
        throw std::invalid_argument(
            "face width: coupling = table: a stage needs a " + std::to_string(spec_.slices) +
            " x " + std::to_string(spec_.slices) +
            " kernel for each mesh kind (coupling_table_sun_planet, coupling_table_planet_ring), "
            "one is " +
            std::to_string(w->rows()) + " x " + std::to_string(w->cols()));
    coupling_sun_planet_ = spec_.coupling_table;
    coupling_planet_ring_ = spec_.coupling_table_planet_ring;
  } else {
    coupling_sun_planet_ =
        FaceCouplingMatrix(spec_.slices, b_sp, spec_.coupling, spec_.coupling_length);
    coupling_planet_ring_ =
        FaceCouplingMatrix(spec_.slices, b_pr, spec_.coupling, spec_.coupling_length);
  }
}

Eigen::Vector2d FaceWidthModel::AxisSlope(const geometry::StagePoses& poses, int body) const {
  if (body < 2) return Eigen::Vector2d::Zero();
  const int i = body - 2;
  const geometry::Vec2 c = poses.planets.at(static_cast<std::size_t>(i)).rotation_centre;
  const double r = c.norm();
  if (!(r > 0)) return Eigen::Vector2d::Zero();
  const Eigen::Vector2d radial = c / r, tangential(-radial.y(), radial.x());
  const Eigen::Vector2d& own = planet_slope_[static_cast<std::size_t>(i)];
  const Eigen::Vector2d given = own.x() * radial + (own.y() + wind_up_slope_) * tangential;
  if (!pins_.active()) return given;
  return given + poses.planets[static_cast<std::size_t>(i)].axis_slope;
}

FaceWidthModel::Misalignment FaceWidthModel::MeshMisalignment(const geometry::StagePoses& poses,
                                                              const StageContact& c) const {
  const bool ring = c.mesh == geometry::MeshKind::kPlanetRing;
  const double b = ring ? planet_ring_width_ : sun_planet_width_;
  const geometry::PotentialContact& p = c.contact;
  // The deflections alone: the wind-up (every pin's tangential slope) and a planet's tilt on its
  // pin under load; the sun and the ring untilted.
  auto wind_up = [&](int body) -> Eigen::Vector2d {
    if (body < 2) return Eigen::Vector2d::Zero();
    const geometry::GearPose& pose = poses.planets.at(static_cast<std::size_t>(body - 2));
    const Eigen::Vector2d pin = pins_.active() ? pose.axis_slope : Eigen::Vector2d::Zero();
    const double r = pose.rotation_centre.norm();
    if (!(r > 0)) return pin;
    const Eigen::Vector2d w =
        wind_up_slope_ * Eigen::Vector2d(-pose.rotation_centre.y() / r, pose.rotation_centre.x() / r);
    return pins_.active() ? Eigen::Vector2d(w + pin) : w;
  };
  const Eigen::Vector2d all = AxisSlope(poses, c.body_a) - AxisSlope(poses, c.body_b);
  const Eigen::Vector2d deflection = wind_up(c.body_a) - wind_up(c.body_b);
  const BodyLead& la = lead_[static_cast<std::size_t>(c.body_a)];
  const BodyLead& lb = lead_[static_cast<std::size_t>(c.body_b)];
  Misalignment m;
  m.deflection = b * p.normal.dot(deflection);
  m.assembly = b * (p.normal.dot(all - deflection) - (p.lever_a * la.slope + p.lever_b * lb.slope));
  return m;
}

double FaceWidthModel::GapChange(const geometry::StagePoses& poses, const StageContact& c,
                                 int s) const {
  const bool ring = c.mesh == geometry::MeshKind::kPlanetRing;
  const double b = ring ? planet_ring_width_ : sun_planet_width_;
  const double z = SliceCentre(s, spec_.slices, b);
  const geometry::PotentialContact& p = c.contact;
  const Eigen::Vector2d tilt = AxisSlope(poses, c.body_a) - AxisSlope(poses, c.body_b);
  const BodyLead& la = lead_[static_cast<std::size_t>(c.body_a)];
  const BodyLead& lb = lead_[static_cast<std::size_t>(c.body_b)];
  return z * p.normal.dot(tilt) - z * (p.lever_a * la.slope + p.lever_b * lb.slope) -
         la.Removed(z) - lb.Removed(z);
}

void FaceWidthModel::Expand(const geometry::StagePoses& poses, const DamageModel& damage,
                            ContactTerms* terms) const {
  // Every buffer is the terms' own and keeps its storage from one call to the next: an evaluation
  // with the same number of contacts allocates nothing here.
  ContactTerms& t = *terms;
  const std::vector<StageContact>& plane = t.plane_contacts;
  const int n = static_cast<int>(plane.size()), S = spec_.slices;
  t.contacts.resize(static_cast<std::size_t>(n * S));
  t.overlap.resize(n * S);
  for (int j = 0; j < n; ++j) {
    const StageContact& c = plane[static_cast<std::size_t>(j)];
    for (int s = 0; s < S; ++s) {
      StageContact& k = t.contacts[static_cast<std::size_t>(j * S + s)];
      k = c;
      k.slice = s;
      k.slices = S;
      k.width_fraction = c.width_fraction / S;
      // The pits covering the slice's centre, measured from the edge z = −b/2 (damage.hpp).
      const double pit = damage.DepthAt(c.body_a, c.body_b, c.contact, (s + 0.5) / S);
      k.pit_depth = pit;
      k.contact.overlap = c.contact.overlap + GapChange(poses, c, s) - pit;
      t.overlap(j * S + s) = k.contact.overlap;
    }
  }
  // Slices of two contacts couple through the body they share; contacts on different meshes of
  // one planet share the planet, whose face is the narrower mesh's: the sun mesh's W. Hence
  // C = C_n ⊗ W_sp when both meshes have the same W, and otherwise
  // C = C_n,other ⊗ W_sp + C_n,ring–ring ⊗ W_pr (the plane matrix split by pairs of contacts).
  const Eigen::MatrixXd& cn = t.plane_compliance;
  auto ring = [&](int j) {
    return plane[static_cast<std::size_t>(j)].mesh == geometry::MeshKind::kPlanetRing;
  };
  const bool one_kernel = coupling_sun_planet_ == coupling_planet_ring_;
  t.compliance_terms.resize(one_kernel ? 1 : 2);
  solvers::KroneckerTerm& first = t.compliance_terms[0];
  first.source = cn;
  first.kernel = coupling_sun_planet_;
  if (!one_kernel) {
    solvers::KroneckerTerm& second = t.compliance_terms[1];
    second.source.setZero(n, n);
    second.kernel = coupling_planet_ring_;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        if (ring(j) && ring(k)) {
          second.source(j, k) = cn(j, k);
          first.source(j, k) = 0.0;
        }
  }
  t.compliance.resize(n * S, n * S);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j) {
      const Eigen::MatrixXd& w = one_kernel || !(ring(j) && ring(k)) ? coupling_sun_planet_
                                                                      : coupling_planet_ring_;
      t.compliance.block(j * S, k * S, S, S) = cn(j, k) * w;
    }
}

std::vector<MeshFaceLoad> FaceLoads(const geometry::Stage& stage, int slices,
                                    const std::vector<StageContact>& contacts,
                                    const Eigen::VectorXd& force) {
  const int planets = stage.planets();
  std::vector<MeshFaceLoad> out(static_cast<std::size_t>(2 * planets));
  const double b_sp = geometry::ContactFaceWidth(stage.sun(), stage.planet(0));
  const double b_pr = geometry::ContactFaceWidth(stage.planet(0), stage.ring());
  for (int m = 0; m < 2 * planets; ++m) {
    MeshFaceLoad& f = out[static_cast<std::size_t>(m)];
    f.planet = m % planets;
    f.ring_mesh = m >= planets;
    f.line_load.assign(static_cast<std::size_t>(slices), 0.0);
  }
  for (std::size_t j = 0; j < contacts.size() && j < static_cast<std::size_t>(force.size()); ++j) {
    const StageContact& c = contacts[j];
    const bool ring = c.mesh == geometry::MeshKind::kPlanetRing;
    const double dz = (ring ? b_pr : b_sp) / slices;
    MeshFaceLoad& f = out[static_cast<std::size_t>((ring ? planets : 0) + c.planet)];
    f.line_load[static_cast<std::size_t>(std::min(c.slice, slices - 1))] +=
        force(static_cast<Eigen::Index>(j)) / dz;
  }
  for (MeshFaceLoad& f : out) SummariseLineLoad(f.ring_mesh ? b_pr : b_sp, &f);
  return out;
}

void SummariseLineLoad(double width, MeshFaceLoad* f) {
  const int slices = static_cast<int>(f->line_load.size());
  double sum = 0;
  for (double w : f->line_load) sum += w;
  f->mean = sum / slices;
  const auto top = std::max_element(f->line_load.begin(), f->line_load.end());
  f->largest_slice = static_cast<int>(top - f->line_load.begin());
  f->largest_z = SliceCentre(f->largest_slice, slices, width);
  f->width = width;
  f->k_h_beta = f->mean > 0 ? *top / f->mean : 1.0;
}

std::vector<std::vector<compliance::FilletStress>> SliceFilletStresses(
    const StageCompliance& compliance, const geometry::Stage& stage,
    const geometry::StagePoses& poses, const std::vector<StageContact>& contacts,
    const Eigen::VectorXd& force, const TangentialLoads* friction) {
  if (force.size() != static_cast<Eigen::Index>(contacts.size()))
    throw std::invalid_argument("SliceFilletStresses: " + std::to_string(force.size()) +
                                " forces for " + std::to_string(contacts.size()) + " contacts");
  const int slices = contacts.empty() ? 1 : contacts.front().slices;
  std::vector<std::vector<compliance::FilletStress>> out(static_cast<std::size_t>(slices));
  for (int s = 0; s < slices; ++s) {
    std::vector<StageContact> own;
    std::vector<double> f;
    TangentialLoads rubbing;
    std::vector<double> phi;
    for (std::size_t j = 0; j < contacts.size(); ++j) {
      if (contacts[j].slice != s) continue;
      own.push_back(contacts[j]);
      // The plane model per unit width at the slice's line load w = S f/b carries w b = S f.
      f.push_back(slices * force(static_cast<Eigen::Index>(j)));
      if (friction != nullptr) {
        phi.push_back(slices * friction->force(static_cast<Eigen::Index>(j)));
        rubbing.tangent.push_back(friction->tangent.at(j));
      }
    }
    if (own.empty()) continue;
    rubbing.force = Eigen::Map<const Eigen::VectorXd>(phi.data(), static_cast<Eigen::Index>(phi.size()));
    out[static_cast<std::size_t>(s)] = compliance.FilletStresses(
        stage, poses, own,
        Eigen::Map<const Eigen::VectorXd>(f.data(), static_cast<Eigen::Index>(f.size())),
        friction != nullptr ? &rubbing : nullptr);
  }
  return out;
}

std::vector<compliance::FilletStress> StateFilletStresses(
    const StageCompliance& compliance, const geometry::Stage& stage,
    const geometry::StagePoses& poses, const std::vector<StageContact>& contacts,
    const Eigen::VectorXd& force, const TangentialLoads* friction,
    std::vector<std::vector<compliance::FilletStress>>* slices) {
  if (contacts.empty() || contacts.front().slices < 2)
    return compliance.FilletStresses(stage, poses, contacts, force, friction);
  std::vector<std::vector<compliance::FilletStress>> own =
      SliceFilletStresses(compliance, stage, poses, contacts, force, friction);
  std::vector<compliance::FilletStress> out;
  for (const auto& s : own) out.insert(out.end(), s.begin(), s.end());
  if (slices != nullptr) *slices = std::move(own);
  return out;
}

void AddFaceStresses(const std::vector<StageContact>& contacts,
                     const std::vector<solvers::LocalTermParameters>& local,
                     const Eigen::VectorXd& force,
                     const std::vector<std::vector<compliance::FilletStress>>& slice_fillets,
                     std::vector<MeshFaceLoad>* loads) {
  if (force.size() != static_cast<Eigen::Index>(contacts.size()) ||
      (!local.empty() && local.size() != contacts.size()))
    throw std::invalid_argument("AddFaceStresses: " + std::to_string(contacts.size()) +
                                " contacts, " + std::to_string(local.size()) +
                                " local terms and " + std::to_string(force.size()) +
                                " forces: must be equal");
  const int slices = static_cast<int>(slice_fillets.size());
  const int planets = static_cast<int>(loads->size()) / 2;
  auto mesh_of = [&](const StageContact& c) {
    return static_cast<std::size_t>((c.mesh == geometry::MeshKind::kPlanetRing ? planets : 0) +
                                    c.planet);
  };
  for (MeshFaceLoad& m : *loads) {
    m.root_stress.assign(static_cast<std::size_t>(slices), 0.0);
    m.root_stress_body.assign(static_cast<std::size_t>(slices), 0);
    m.hertz_pressure.assign(static_cast<std::size_t>(slices), 0.0);
  }
  for (std::size_t j = 0; j < contacts.size(); ++j) {
    const StageContact& c = contacts[j];
    const double f = force(static_cast<Eigen::Index>(j));
    if (local.empty() || !(f > 0) || c.contact.kind != geometry::ContactKind::kInvolute) continue;
    double& p = loads->at(mesh_of(c)).hertz_pressure.at(static_cast<std::size_t>(c.slice));
    p = std::max(p, solvers::HertzPressure(local[j], f));
  }
  for (int s = 0; s < slices; ++s) {
    for (const compliance::FilletStress& fillet : slice_fillets[static_cast<std::size_t>(s)]) {
      // The mesh whose loaded contact of this slice sits nearest on the fillet's body.
      const int teeth = fillet.table->teeth();
      int nearest = teeth + 1;
      std::size_t mesh = 0;
      for (std::size_t j = 0; j < contacts.size(); ++j) {
        const StageContact& c = contacts[j];
        if (c.slice != s || !(force(static_cast<Eigen::Index>(j)) > 0)) continue;
        if (c.body_a != fillet.body && c.body_b != fillet.body) continue;
        const int tooth = c.body_a == fillet.body ? c.contact.tooth_a : c.contact.tooth_b;
        const int d = ((tooth - fillet.tooth) % teeth + teeth) % teeth;
        const int distance = std::min(d, teeth - d);
        if (distance < nearest) {
          nearest = distance;
          mesh = mesh_of(c);
        }
      }
      if (nearest > teeth) continue;
      MeshFaceLoad& m = loads->at(mesh);
      for (double sigma : fillet.sigma) {
        if (sigma > m.root_stress[static_cast<std::size_t>(s)]) {
          m.root_stress[static_cast<std::size_t>(s)] = sigma;
          m.root_stress_body[static_cast<std::size_t>(s)] = fillet.body;
        }
      }
    }
  }
}

}  // namespace epicycle::transmission
