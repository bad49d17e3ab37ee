// The load across the face width of a quasi-static run (face_width_files.hpp).
#include "epicycle/report/face_width_files.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "epicycle/geometry/plane.hpp"
#include "epicycle/report/provenance.hpp"

namespace epicycle::report {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The maps' columns at most: positions beyond share a column (its largest line load).
constexpr int kMapColumns = 360;

std::string Head(const nlohmann::json& provenance, int slices, const std::vector<double>& widths,
                 bool stresses) {
  std::string head = ProvenanceCsvLine(provenance);
  head += "# slice centres z [mm] of a face of width b: -b/2 + (s + 1/2) b/S, S = " +
          std::to_string(slices) + "; b = " + fmt::format("{:g}", widths.front() * 1e3) +
          " mm (sun meshes), " + fmt::format("{:g}", widths.back() * 1e3) + " mm (ring meshes)\n";
  head += "carrier_deg,mesh,converged,K_Hbeta,largest_z_mm,mean_N_per_mm";
  for (int s = 1; s <= slices; ++s) head += ",w" + std::to_string(s) + "_N_per_mm";
  if (stresses)
    head += ",root_stress_max_MPa,root_stress_gear,root_stress_z_mm,hertz_pressure_max_MPa,"
            "hertz_pressure_z_mm";
  if (stresses) {
    for (int s = 1; s <= slices; ++s) head += ",sigmaF" + std::to_string(s) + "_MPa";
    for (int s = 1; s <= slices; ++s) head += ",pH" + std::to_string(s) + "_MPa";
  }
  return head + "\n";
}

}  // namespace

FaceMeshes StageFaceMeshes(const geometry::Stage& stage) {
  FaceMeshes m;
  for (const bool ring : {false, true}) {
    for (int i = 0; i < stage.planets(); ++i) {
      m.names.push_back(geometry::MeshName(
          i, ring ? geometry::MeshKind::kPlanetRing : geometry::MeshKind::kSunPlanet));
      m.widths.push_back(ring ? geometry::ContactFaceWidth(stage.planet(i), stage.ring())
                              : geometry::ContactFaceWidth(stage.sun(), stage.planet(i)));
    }
  }
  return m;
}

std::string FaceWidthText(const std::vector<transmission::MeshFaceSummary>& faces) {
  if (faces.empty()) return "";
  std::string t =
      "\n  mesh             K_Hbeta max  K_Hbeta mean  at carrier deg  largest load at z mm  "
      "max L_i K_Hbeta\n";
  for (const transmission::MeshFaceSummary& f : faces)
    t += fmt::format("  {:<16} {:<12.6f} {:<13.6f} {:<15.4f} {:<21.3f} {:.6f}\n", f.mesh,
                     f.k_h_beta_max, f.k_h_beta_mean, geometry::Deg(f.carrier_angle),
                     f.largest_z * 1e3, f.k_gamma_k_h_beta_max);
  if (faces.front().stresses) {
    t += "\n  mesh             root stress max MPa  gear      at z mm  Hertz pressure max MPa  "
         "at z mm\n";
    for (const transmission::MeshFaceSummary& f : faces)
      t += fmt::format("  {:<16} {:<20.2f} {:<9} {:<8.3f} {:<23.2f} {:.3f}\n", f.mesh,
                       f.root_stress_max * 1e-6, f.root_stress_gear, f.root_stress_z * 1e3,
                       f.hertz_pressure_max * 1e-6, f.hertz_pressure_z * 1e3);
  }
  return t;
}

void KHBetaPlot::Add(double x, const std::vector<transmission::MeshFaceLoad>& loads) {
  for (std::size_t m = 0; m < meshes_.size() && m < loads.size(); ++m) {
    x_[m].push_back(x);
    k_[m].push_back(loads[m].k_h_beta);
  }
}

bool KHBetaPlot::empty() const {
  return std::all_of(x_.begin(), x_.end(), [](const auto& x) { return x.empty(); });
}

std::string KHBetaPlot::Svg(const std::string& title, const std::string& x_label) const {
  LinePlot k;
  k.title = title + ": face load factor K_Hbeta";
  k.x_label = x_label;
  k.y_label = "K_Hbeta [-]";
  k.y_references = {1.0};
  for (std::size_t m = 0; m < meshes_.size(); ++m) k.series.push_back({meshes_[m], x_[m], k_[m]});
  return RenderSvg(k);
}

FaceLoadFiles::FaceLoadFiles(const std::string& base, const nlohmann::json& provenance, int slices,
                             std::vector<std::string> meshes, std::vector<double> widths,
                             int positions, bool stresses)
    : base_(base),
      csv_(base + "_face_load.csv", Head(provenance, slices, widths, stresses)),
      slices_(slices),
      positions_(std::max(1, positions)),
      columns_(std::min(kMapColumns, std::max(1, positions))),
      stresses_(stresses),
      meshes_(std::move(meshes)),
      widths_(std::move(widths)),
      k_h_beta_(meshes_) {
  map_.assign(meshes_.size(),
              std::vector<double>(static_cast<std::size_t>(columns_ * slices_), kNaN));
}

void FaceLoadFiles::Write(const transmission::PositionResult& r) {
  const double deg = geometry::Deg(r.carrier_angle);
  if (seen_ == 0) first_angle_ = deg;
  last_angle_ = deg;
  const int column = std::min(columns_ - 1, static_cast<int>(static_cast<long>(seen_) * columns_ /
                                                            positions_));
  ++seen_;
  std::string lines;
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    const bool ok = r.converged && m < r.face_loads.size();
    std::string line = fmt::format("{:.6f},{},{}", deg, meshes_[m], ok ? 1 : 0);
    if (!ok) {
      line += ",,,";
      for (int s = 0; s < slices_; ++s) line += ",";
      if (stresses_) line += std::string(static_cast<std::size_t>(5 + 2 * slices_), ',');
      lines += line + "\n";
      continue;
    }
    const transmission::MeshFaceLoad& f = r.face_loads[m];
    line += fmt::format(",{},{},{}", Cell(f.k_h_beta), Cell(f.largest_z * 1e3), Cell(f.mean * 1e-3));
    for (int s = 0; s < slices_; ++s) {
      const double w = f.line_load[static_cast<std::size_t>(s)] * 1e-3;  // [N/mm]
      line += ',';
      line += Cell(w);
      double& cell = map_[m][static_cast<std::size_t>(s * columns_ + column)];
      cell = std::isnan(cell) ? w : std::max(cell, w);
    }
    if (stresses_) {
      // The largest over the slices (the first slice of a tie); a state without fillets: empty.
      int rs = -1, hp = -1;
      for (int s = 0; s < static_cast<int>(f.root_stress.size()); ++s) {
        const auto k = static_cast<std::size_t>(s);
        if (rs < 0 || f.root_stress[k] > f.root_stress[static_cast<std::size_t>(rs)]) rs = s;
        if (hp < 0 || f.hertz_pressure[k] > f.hertz_pressure[static_cast<std::size_t>(hp)]) hp = s;
      }
      if (rs < 0) {
        line += ",,,,,";
      } else {
        const auto at = static_cast<std::size_t>(rs), h = static_cast<std::size_t>(hp);
        line += fmt::format(",{},{},{},{},{}", Cell(f.root_stress[at] * 1e-6),
                            transmission::BodyName(f.root_stress_body[at]),
                            Cell(transmission::SliceCentre(rs, slices_, f.width) * 1e3),
                            Cell(f.hertz_pressure[h] * 1e-6),
                            Cell(transmission::SliceCentre(hp, slices_, f.width) * 1e3));
      }
      // Per slice: the root stress, then the Hertz pressure [MPa] (empty without fillets).
      for (const std::vector<double>* v : {&f.root_stress, &f.hertz_pressure})
        for (int s = 0; s < slices_; ++s) {
          line += ',';
          if (s < static_cast<int>(v->size()))
            AppendCell(line, (*v)[static_cast<std::size_t>(s)] * 1e-6);
        }
    }
    lines += line + "\n";
  }
  if (r.converged) k_h_beta_.Add(deg, r.face_loads);
  csv_.Write(lines);
}

void FaceLoadFiles::WritePlots(const std::string& title) const {
  if (seen_ == 0) return;
  std::vector<HeatMap> maps;
  const double step = positions_ > 1 ? (last_angle_ - first_angle_) / (positions_ - 1) : 1.0;
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    HeatMap h;
    h.title = meshes_[m];
    h.x_label = "carrier angle [deg]";
    h.y_label = "z [mm]";
    h.unit = "N/mm";
    h.x0 = first_angle_ - 0.5 * step;
    h.x1 = last_angle_ + 0.5 * step;
    h.y0 = -0.5 * widths_[m] * 1e3;
    h.y1 = 0.5 * widths_[m] * 1e3;
    h.columns = columns_;
    h.rows = slices_;
    h.values = map_[m];
    maps.push_back(std::move(h));
  }
  WriteTextFile(base_ + "_face_load.svg",
                RenderHeatMaps(title + ": load per unit face width", maps));
  WriteTextFile(base_ + "_k_hbeta.svg", k_h_beta_.Svg(title, "carrier angle [deg]"));
}

}  // namespace epicycle::report
