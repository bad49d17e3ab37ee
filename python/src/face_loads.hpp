// The load across the face width of a sliced run as numpy arrays: per row (a quasi-static position
// or a dynamic step) and mesh, the columns of the face-load CSV and of the steps file
// (report/face_width_files.hpp).
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "common.hpp"
#include "epicycle/transmission/face_width.hpp"

namespace epicycle::python {

/// Adds to `f` `face_meshes` (the M mesh names), `k_hbeta` and `largest_load_z_mm` [mm] (rows, M)
/// and, with `slices` S > 0, `line_load_N_per_mm` (rows, M, S) and, with `stresses`,
/// `root_stress_MPa` and `hertz_pressure_MPa` (rows, M, S) (MeshFaceLoad's line_load, root_stress,
/// hertz_pressure). A row that is null or carries another count of meshes (a position that did
/// not converge, a step without face loads) is NaN throughout, as is a slice a load lacks.
inline void AddFaceLoads(const std::vector<std::string>& meshes, int slices, bool stresses,
                         const std::vector<const std::vector<transmission::MeshFaceLoad>*>& rows,
                         py::dict* f) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const std::size_t m_count = meshes.size();
  const auto s_count = static_cast<std::size_t>(slices > 0 ? slices : 0);
  std::vector<double> k_h_beta, largest_z, line_load, root_stress, hertz_pressure;
  // Slice s of x's `v` times `scale`; NaN without x or where `v` has no slice s.
  const auto slice = [](const transmission::MeshFaceLoad* x,
                        std::vector<double> transmission::MeshFaceLoad::*v, std::size_t s,
                        double scale) {
    return x != nullptr && s < (x->*v).size() ? (x->*v)[s] * scale : kNaN;
  };
  for (const std::vector<transmission::MeshFaceLoad>* row : rows)
    for (std::size_t m = 0; m < m_count; ++m) {
      const transmission::MeshFaceLoad* x =
          row != nullptr && row->size() == m_count ? &(*row)[m] : nullptr;
      k_h_beta.push_back(x != nullptr ? x->k_h_beta : kNaN);
      largest_z.push_back(x != nullptr ? x->largest_z * 1e3 : kNaN);
      for (std::size_t s = 0; s < s_count; ++s) {
        line_load.push_back(slice(x, &transmission::MeshFaceLoad::line_load, s, 1e-3));  // [N/mm]
        if (!stresses) continue;
        root_stress.push_back(
            slice(x, &transmission::MeshFaceLoad::root_stress, s, 1e-6));  // [MPa]
        hertz_pressure.push_back(slice(x, &transmission::MeshFaceLoad::hertz_pressure, s, 1e-6));
      }
    }
  const auto count = static_cast<py::ssize_t>(rows.size());
  const auto width = static_cast<py::ssize_t>(m_count);
  (*f)["face_meshes"] = meshes;
  (*f)["k_hbeta"] = Array2(std::move(k_h_beta), count, width);
  (*f)["largest_load_z_mm"] = Array2(std::move(largest_z), count, width);
  if (s_count == 0) return;
  const std::vector<py::ssize_t> shape{count, width, static_cast<py::ssize_t>(s_count)};
  (*f)["line_load_N_per_mm"] = ArrayOfShape(std::move(line_load), shape);
  if (!stresses) return;
  (*f)["root_stress_MPa"] = ArrayOfShape(std::move(root_stress), shape);
  (*f)["hertz_pressure_MPa"] = ArrayOfShape(std::move(hertz_pressure), shape);
}

}  // namespace epicycle::python
