#include "epicycle/dynamics/dynamic_factor.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/io/units.hpp"

namespace epicycle::dynamics {

namespace {

int MeshOf(const transmission::StageContact& c) { return geometry::MeshIndex(c.planet, c.mesh); }

}  // namespace

MotionLoads::MotionLoads(const geometry::Stage& stage) : peak_(stage.meshes().size(), 0.0) {}

void MotionLoads::Add(const DynamicSample& s) {
  ++outputs_;
  const Evaluation& e = s.evaluation;
  if (!e.ok) return;
  ++steps_;
  std::vector<double> mesh(peak_.size(), 0.0);
  for (int j = 0; j < e.terms.size(); ++j)
    mesh.at(static_cast<std::size_t>(MeshOf(e.terms.contacts[j]))) += e.total_force(j);
  for (std::size_t q = 0; q < mesh.size(); ++q) peak_[q] = std::max(peak_[q], mesh[q]);
  // The pressures of the forces the stresses use (with damping), when the step has stresses.
  if (!s.fillet_stress.empty())
    pressure_.Add(e.terms.contacts, e.terms.local, e.total_force, s.time);
}

RestReference SolveRestReference(
    const DynamicModel& model, const SimulationOptions& options, int count,
    const std::function<double(int)>& angle,
    const std::function<void(const transmission::PositionResult&)>& each) {
  transmission::QuasiStaticOptions qo;
  qo.backend = options.backend;
  qo.contact = options.contact;
  qo.friction = model.settings().friction;
  qo.sun_speed = model.settings().sun_speed;
  RestReference out;
  out.peak_mesh_force.assign(model.stage_model().stage().meshes().size(), 0.0);
  transmission::SweepEach(
      model.stage_model(), model.loads(), count, angle, qo,
      [&](const transmission::PositionResult& r, int) {
        if (!r.converged && r.status == transmission::StageStatus::kFrictionNotSettled) {
          ++out.left_out;
          return;
        }
        if (!r.converged)
          throw std::runtime_error(
              fmt::format("the quasi-static reference at carrier {:.6g} deg failed: {}",
                          r.carrier_angle * 180 / std::numbers::pi, r.message));
        std::vector<double> mesh(out.peak_mesh_force.size(), 0.0);
        for (std::size_t j = 0; j < r.problem.contacts.size(); ++j)
          mesh.at(static_cast<std::size_t>(MeshOf(r.problem.contacts[j]))) +=
              std::max(0.0, r.solution.force(static_cast<Eigen::Index>(j)));
        for (std::size_t q = 0; q < mesh.size(); ++q)
          out.peak_mesh_force[q] = std::max(out.peak_mesh_force[q], mesh[q]);
        if (each) each(r);
      });
  if (count > 0 && out.left_out == count)
    throw std::runtime_error(
        "the quasi-static reference: the friction of no position settled (docs/quasistatic.md "
        "\"Friction at rest\")");
  return out;
}

DynamicFactor DynamicLoadFactor(const DynamicModel& model, const SimulationOptions& options,
                                const std::vector<double>& output_times, const MotionLoads& loads) {
  const geometry::Stage& stage = model.stage_model().stage();
  if (loads.steps() == 0 || output_times.empty())
    throw std::invalid_argument("DynamicLoadFactor: the run has no output step to compare");
  if (loads.peak_mesh_force().size() != stage.meshes().size())
    throw std::invalid_argument("DynamicLoadFactor: the peaks are not of this stage's meshes");
  transmission::SweepAccumulator summary(stage.planets());
  const RestReference rest = SolveRestReference(
      model, options, static_cast<int>(output_times.size()),
      [&](int k) { return model.CarrierAngle(output_times[static_cast<std::size_t>(k)]); },
      [&](const transmission::PositionResult& r) { summary.Add(r); });
  const std::vector<double>& peak = rest.peak_mesh_force;
  DynamicFactor out;
  out.quasi_static = summary.Result();
  out.reference_left_out = rest.left_out;
  for (std::size_t q = 0; q < peak.size(); ++q) {
    if (!(peak[q] > 0)) continue;
    const double f = loads.peak_mesh_force()[q] / peak[q];
    if (!(f <= out.value)) {  // NaN at first
      out.value = f;
      out.mesh = static_cast<int>(q);
      out.mesh_name = stage.meshes()[q].name;
      out.peak_dynamic = loads.peak_mesh_force()[q];
      out.peak_quasi_static = peak[q];
    }
  }
  out.source = fmt::format(
      "the dynamic run at {:.6g} rpm: largest {} force in motion {:.6g} N over {:.6g} N at rest "
      "at the same {} carrier angles{}",
      io::RadPerSecondToRpm(std::abs(model.sun_speed())), out.mesh_name, out.peak_dynamic,
      out.peak_quasi_static, output_times.size(),
      model.settings().friction.law == transmission::FrictionLaw::kOff
          ? std::string()
          : fmt::format(", friction {} at rest as in motion{}",
                        transmission::FrictionLawName(model.settings().friction.law),
                        rest.left_out > 0 ? fmt::format(" ({} positions whose friction did not "
                                                        "settle left out)",
                                                        rest.left_out)
                                          : std::string()));
  return out;
}

MotionRating RateInMotion(const transmission::RatingInputs& inputs, const DynamicModel& model,
                          const SimulationOptions& options, const std::vector<double>& output_times,
                          const MotionLoads& loads,
                          const std::vector<transmission::RootStressSummary>& root_stress) {
  transmission::CheckRatingInputs(inputs, "a rating in motion");
  MotionRating out;
  out.factor = DynamicLoadFactor(model, options, output_times, loads);
  const double kv = std::max(1.0, out.factor.value);
  std::string source = out.factor.source;
  if (!(out.factor.value >= 1))
    source += fmt::format(" = {:.6g}, below the standard's least K_v: 1 used", out.factor.value);
  transmission::MotionStresses motion{
      root_stress, loads.contact_pressure(),
      fmt::format("the dynamic run at {:.6g} rpm",
                  io::RadPerSecondToRpm(std::abs(model.sun_speed())))};
  out.rating = transmission::RateStage(inputs, model.stage_model().stage(), out.factor.quasi_static,
                                       kv, source, &motion);
  return out;
}

MotionRating RateRun(const transmission::RatingInputs& inputs, const DynamicModel& model,
                     const SimulationOptions& options, const RunSpan& span,
                     const MotionLoads& loads,
                     const std::vector<transmission::RootStressSummary>& root_stress) {
  std::vector<double> times = span.OutputTimes();
  times.resize(static_cast<std::size_t>(std::min<long>(loads.outputs(), std::ssize(times))));
  return RateInMotion(inputs, model, options, times, loads, root_stress);
}

}  // namespace epicycle::dynamics
