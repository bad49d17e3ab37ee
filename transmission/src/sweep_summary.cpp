#include "epicycle/transmission/sweep_summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "epicycle/transmission/record.hpp"

namespace epicycle::transmission {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

double SweepSummary::LsrMin() const {
  double v = kNaN;
  for (double x : lsr_min) v = std::isnan(v) ? x : std::min(v, x);
  return v;
}

double SweepSummary::LsrMax() const {
  double v = kNaN;
  for (double x : lsr_max) v = std::isnan(v) ? x : std::max(v, x);
  return v;
}

namespace {

int CheckedPlanets(int planets) {
  if (planets < 1)
    throw std::invalid_argument("SummariseSweep: planets = " + std::to_string(planets) +
                                ": must be >= 1");
  return planets;
}

}  // namespace

void FaceLoadTracker::Add(const std::vector<MeshFaceLoad>& loads,
                          const std::vector<double>& factors, double carrier_angle) {
  if (faces_.empty()) {
    for (const MeshFaceLoad& m : loads) {
      MeshFaceSummary f;
      f.planet = m.planet;
      f.ring_mesh = m.ring_mesh;
      f.mesh = geometry::MeshName(
          m.planet, m.ring_mesh ? geometry::MeshKind::kPlanetRing : geometry::MeshKind::kSunPlanet);
      f.k_h_beta_max = -1;
      f.k_gamma_k_h_beta_max = -1;
      f.misalignment_assembly = m.misalignment_assembly;
      f.misalignment_deflection = m.misalignment_deflection;
      faces_.push_back(f);
    }
    mean_.resize(faces_.size());
  }
  for (std::size_t m = 0; m < loads.size() && m < faces_.size(); ++m) {
    const MeshFaceLoad& load = loads[m];
    MeshFaceSummary& f = faces_[m];
    mean_[m].Add(load.k_h_beta);
    if (load.k_h_beta > f.k_h_beta_max) {
      f.k_h_beta_max = load.k_h_beta;
      f.carrier_angle = carrier_angle;
      f.largest_z = load.largest_z;
    }
    const auto planet = static_cast<std::size_t>(load.planet);
    const double factor = planet < factors.size() ? factors[planet] : kNaN;
    f.k_gamma_k_h_beta_max = std::max(f.k_gamma_k_h_beta_max, factor * load.k_h_beta);
    const int slices = static_cast<int>(load.line_load.size());
    for (int s = 0; s < static_cast<int>(load.root_stress.size()); ++s) {
      const auto k = static_cast<std::size_t>(s);
      f.stresses = true;
      if (load.root_stress[k] > f.root_stress_max) {
        f.root_stress_max = load.root_stress[k];
        f.root_stress_gear = BodyName(load.root_stress_body[k]);
        f.root_stress_z = SliceCentre(s, slices, load.width);
        f.root_stress_angle = carrier_angle;
      }
      if (load.hertz_pressure[k] > f.hertz_pressure_max) {
        f.hertz_pressure_max = load.hertz_pressure[k];
        f.hertz_pressure_z = SliceCentre(s, slices, load.width);
        f.hertz_pressure_angle = carrier_angle;
      }
    }
  }
}

std::vector<MeshFaceSummary> FaceLoadTracker::Result() const {
  std::vector<MeshFaceSummary> s = faces_;
  for (std::size_t m = 0; m < s.size(); ++m) s[m].k_h_beta_mean = mean_[m].mean();
  return s;
}

void VisitFaceWidth(RecordVisitor& visit, const std::vector<MeshFaceSummary>& faces) {
  if (faces.empty()) return;
  visit.BeginList("face_width");
  for (const MeshFaceSummary& f : faces) {
    visit.Item();
    visit.Text("mesh", f.mesh);
    visit.Number("K_Hbeta_max", f.k_h_beta_max);
    visit.Number("K_Hbeta_mean", f.k_h_beta_mean);
    visit.Number("carrier_angle_at_max_deg", f.carrier_angle * 180 / std::numbers::pi);
    visit.Number("largest_load_z_mm", f.largest_z * 1e3);
    visit.Number("K_gamma_K_Hbeta_max", f.k_gamma_k_h_beta_max);
    if (f.stresses) {
      visit.Number("root_stress_max_MPa", f.root_stress_max * 1e-6);
      visit.Text("root_stress_gear", f.root_stress_gear);
      visit.Number("root_stress_z_mm", f.root_stress_z * 1e3);
      visit.Number("root_stress_carrier_angle_deg", f.root_stress_angle * 180 / std::numbers::pi);
      visit.Number("hertz_pressure_max_MPa", f.hertz_pressure_max * 1e-6);
      visit.Number("hertz_pressure_z_mm", f.hertz_pressure_z * 1e3);
      visit.Number("hertz_pressure_carrier_angle_deg",
                   f.hertz_pressure_angle * 180 / std::numbers::pi);
    }
  }
  visit.EndList();
}

SweepAccumulator::SweepAccumulator(int planets)
    : planets_(CheckedPlanets(planets)),
      lsr_(static_cast<std::size_t>(planets)),
      root_stress_(BodyNames(PlanetBody(planets))) {}

void SweepAccumulator::Add(const PositionResult& r) {
  const auto n = static_cast<std::size_t>(planets_);
  ++positions_;
  friction_ = friction_ || r.friction;
  if (!r.converged) return;
  if (r.load_sharing.size() != n)
    throw std::invalid_argument(
        "SummariseSweep: a converged position has " + std::to_string(r.load_sharing.size()) +
        " load-sharing ratios for " + std::to_string(planets_) + " planets");
  for (std::size_t i = 0; i < n; ++i) lsr_[i].Add(r.load_sharing[i]);
  te_.Add(r.transmission_error);
  displacement_.Add(r.sun_displacement.norm());
  k_gamma_.Add(MeshLoadFactor(r));
  if (!r.helical.planets.empty()) {
    AddHelicalLoads(r.helical, 1.0, &helical_sum_);
    ++helical_count_;
  }
  if (r.pin_tilts_carrier.size() == n) {
    pin_radial_.resize(n);
    pin_tangential_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      pin_radial_[i].Add(r.pin_tilts_carrier[i].x());
      pin_tangential_[i].Add(r.pin_tilts_carrier[i].y());
    }
    pin_iterations_.Add(r.geometric_iterations);
  }
  if (r.friction) {
    efficiency_.Add(r.Efficiency());
    friction_power_.Add(r.friction_power);
    iterations_.Add(r.geometric_iterations);
  }
  // The load across the face width, when the positions carry slices.
  if (!r.face_loads.empty()) faces_.Add(r.face_loads, LoadSharingFactors(r), r.carrier_angle);
  // Root stresses and contact pressures, when the positions carry stresses.
  if (!r.fillet_stress.empty()) {
    root_stress_.Add(r.fillet_stress, r.root_stress, r.carrier_angle);
    pressure_.Add(r.problem.contacts, r.problem.data.local, r.solution.force, r.carrier_angle);
  }
}

SweepSummary SweepAccumulator::Result() const {
  SweepSummary s;
  s.positions = positions_;
  s.converged = static_cast<int>(te_.count());
  // No converged position: NaN everywhere (the accumulators' empty rule).
  for (const Accumulator& a : lsr_) {
    s.lsr_mean.push_back(a.mean());
    s.lsr_min.push_back(a.min());
    s.lsr_max.push_back(a.max());
  }
  s.transmission_error_min = te_.min();
  s.transmission_error_max = te_.max();
  s.sun_displacement_max = displacement_.max();
  s.k_gamma = k_gamma_.empty() ? kNaN : std::max(0.0, k_gamma_.max());
  s.k_gamma_mean = kNaN;
  if (s.converged > 0) {
    s.k_gamma_mean = 0.0;
    for (double m : s.lsr_mean)
      s.k_gamma_mean = std::max(s.k_gamma_mean, static_cast<double>(planets_) * m);
  }
  s.root_stress = root_stress_.Result();
  s.contact_pressure = pressure_.Result();
  s.face_width = faces_.Result();
  if (helical_count_ > 0) AddHelicalLoads(helical_sum_, 1.0 / helical_count_, &s.helical_mean);
  for (std::size_t i = 0; i < pin_radial_.size(); ++i)
    s.pin_tilts.push_back({pin_radial_[i].mean(), pin_radial_[i].min(), pin_radial_[i].max(),
                           pin_tangential_[i].mean(), pin_tangential_[i].min(),
                           pin_tangential_[i].max()});
  if (!pin_radial_.empty()) {
    s.pin_iterations_mean = pin_iterations_.mean();
    s.pin_iterations_max = pin_iterations_.max();
  }
  s.friction = friction_;
  s.efficiency_mean = efficiency_.mean();
  s.efficiency_min = efficiency_.min();
  s.friction_power_mean = friction_power_.mean();
  s.friction_iterations_mean = iterations_.mean();
  return s;
}

SweepSummary SummariseSweep(const std::vector<PositionResult>& results, int planets) {
  SweepAccumulator a(planets);
  for (const PositionResult& r : results) a.Add(r);
  return a.Result();
}

}  // namespace epicycle::transmission
