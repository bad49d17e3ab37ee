// A quasi-static run's files and console text (quasistatic_run_files.hpp).
#include "epicycle/report/quasistatic_run_files.hpp"

#include <filesystem>
#include <numbers>

#include <fmt/format.h>

#include "epicycle/geometry/plane.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/report/files.hpp"
#include "epicycle/report/ratings.hpp"
#include "epicycle/report/record_json.hpp"

namespace epicycle::report {

QuasiStaticRunFiles::QuasiStaticRunFiles(Options options, nlohmann::json provenance)
    : options_(std::move(options)), provenance_(std::move(provenance)) {}

QuasiStaticRunFiles::~QuasiStaticRunFiles() = default;

void QuasiStaticRunFiles::Start(const transmission::QuasiStaticPlan& p) {
  const int n = p.stage->planets();
  sun_name_ = transmission::SunSupportName(p.scene->supports.sun);
  scene_name_ = p.scene->name;
  std::filesystem::create_directories(options_.out);
  if (!options_.dump.empty()) std::filesystem::create_directories(options_.dump);
  base_ = options_.out + "/quasistatic";
  files_ = std::make_unique<QuasiStaticFiles>(base_, provenance_, n, p.friction,
                                              p.compliance->has_root_stress());
  plots_ = std::make_unique<QuasiStaticPlots>(base_, n, p.positions,
                                              360.0 / p.stage->ring().teeth(),  // mesh cycle
                                              geometry::Deg(p.span));
  if (p.scene->face_width.active()) {
    FaceMeshes meshes = StageFaceMeshes(*p.stage);
    faces_ = std::make_unique<FaceLoadFiles>(base_, provenance_, p.scene->face_width.slices,
                                             std::move(meshes.names), std::move(meshes.widths),
                                             p.positions, p.compliance->has_root_stress());
  }
}

void QuasiStaticRunFiles::Position(const transmission::PositionResult& r, int k) {
  files_->Write(r);
  plots_->Add(r);
  if (faces_) faces_->Write(r);
  if (options_.dump.empty() || r.problem.data.compliance.size() == 0) return;
  WriteStageProblemFile(options_.dump,
                        fmt::format("{}_{}_{}_{:03d}", options_.dump_stem, sun_name_,
                                    options_.linear ? "linear" : "local", k),
                        r.problem.data, provenance_,
                        fmt::format("{} at carrier {:.4f} deg, sun {}, back end {}: {}",
                                    scene_name_, geometry::Deg(r.carrier_angle), sun_name_,
                                    options_.backend, r.converged ? "converged" : r.message));
}

void QuasiStaticRunFiles::Close() {
  files_->Close();
  if (faces_) faces_->Close();
}

void QuasiStaticRunFiles::Finish(const transmission::QuasiStaticRecord& record) {
  WriteTextFile(base_ + "_summary.json", QuasiStaticRecordJson(record, provenance_).dump(2) + "\n");
  plots_->Write(scene_name_, sun_name_);
  if (faces_) faces_->WritePlots(scene_name_ + ", sun " + sun_name_);
}

std::string QuasiStaticPlanText(const transmission::QuasiStaticPlan& p, const std::string& backend,
                                bool cold, int threads) {
  const transmission::Scene& scene = *p.scene;
  std::string t =
      fmt::format("{}: {} planets, sun {}, input torque {:.1f} N m, back end {}\n", scene.name,
                  p.stage->planets(), transmission::SunSupportName(scene.supports.sun),
                  scene.loads.sun_torque, backend);
  for (const std::string& m : p.compliance->tables().messages()) t += "  " + m + "\n";
  for (const std::string& d : scene.damage.Describe()) t += "  " + d + "\n";
  t += fmt::format(
      "  {} positions from {:.4f} deg ({:.2f} s for the tables), {}, {}\n", p.positions,
      geometry::Deg(p.first_angle), p.table_seconds,
      cold ? "every position cold" : "each warm-started from its neighbour",
      threads == 0 ? std::string("one thread per core") : fmt::format("{} thread(s)", threads));
  if (p.friction)
    t += fmt::format("  friction {} at rest, sun at {:.1f} rpm\n",
                     transmission::FrictionLawName(p.options->friction.law),
                     io::RadPerSecondToRpm(p.options->sun_speed));
  return t;
}

std::string QuasiStaticRecordText(const transmission::QuasiStaticRecord& r,
                                  const std::string& base) {
  const transmission::SweepSummary& s = r.summary;
  const int planets = static_cast<int>(s.lsr_mean.size());
  std::string t = fmt::format(
      "\n  planet   LSR mean     LSR min      LSR max      (ideal 1/n = {:.6f})\n", 1.0 / planets);
  for (int i = 0; i < planets; ++i) {
    const char* f = "{:<12.6f}";
    t += fmt::format("  {:<8d} {} {} {}\n", i + 1, Figure(s.lsr_mean[i], f, "-           "),
                     Figure(s.lsr_min[i], f, "-           "), Figure(s.lsr_max[i], f, "-"));
  }
  if (r.converged_positions > 0) {
    t += fmt::format("  K_gamma (max L_i)            {:.6f}\n", s.k_gamma);
    t += fmt::format(
        "  transmission error           {:.3f} .. {:.3f} urad (peak to peak {:.3f} urad)\n",
        s.transmission_error_min * 1e6, s.transmission_error_max * 1e6,
        s.TransmissionErrorPeakToPeak() * 1e6);
    t += fmt::format("  sun displacement, largest    {:.3f} um\n", s.sun_displacement_max * 1e6);
    if (r.friction)
      t += fmt::format(
          "  efficiency mean {:.6f} (min {:.6f}), friction loss mean {:.3f} W, {:.2f} iterations\n",
          s.efficiency_mean, s.efficiency_min, s.friction_power_mean, s.friction_iterations_mean);
  } else {
    t += "  K_gamma, transmission error, sun displacement: - (no position converged)\n";
  }
  t += FaceWidthText(s.face_width);
  t += RootStressText(s.root_stress, "carrier deg", 180.0 / std::numbers::pi);
  t += ContactPressureText(s.contact_pressure, "carrier deg", 180.0 / std::numbers::pi);
  if (r.rating) t += RatingText(*r.rating);
  t += fmt::format("  positions converged          {} of {}, {:.3f} s ({:.3f} ms per position)\n",
                   r.converged_positions, r.positions, r.sweep_seconds,
                   1e3 * r.sweep_seconds / r.positions);
  for (const std::string& f : r.failures) t += "  FAILED " + f + "\n";
  if (r.failures_not_listed > 0)
    t += fmt::format("  and {} more failed (status and message in {}_positions.csv)\n",
                     r.failures_not_listed, base);
  return t;
}

}  // namespace epicycle::report
