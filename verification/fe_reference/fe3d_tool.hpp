// The fe_reference tool's 3D subcommands (fe3d_tool.cpp).
#pragma once

#include <string>
#include <vector>

namespace epicycle::fe_reference {

struct Fe3dCommandArgs {
  std::string scene, name = "case", out = "fe3d-out", csv = "fe3d.csv", ccx = "ccx";
  double angle_deg = 13.5;     ///< gear-1 position [deg]
  double misalignment_um = 0;  ///< F_β [µm]
  double face_width_mm = 0;    ///< b [mm]; 0: the pair's
  int layers = 10;             ///< [-]
  double refinement = 1;       ///< divides every in-plane size [-]
  bool plane_strain = false;   ///< one layer, u_z = 0
  std::string axial_support = "hubs";  ///< Fe3dOptions::axial_support: hubs, mid-plane, body
  double plane_k = 13.12;      ///< c′ of the plane model for the steps' estimate [N/(mm·µm)]
  /// The steps' rotations as multiples of the estimate [-] (RunFe3d's step_scales).
  std::vector<double> step_scales{0.94, 1.06};
  int threads = 1;             ///< ccx's OMP_NUM_THREADS
  double tooth_size_per_module = 0;  ///< in-plane size on the sector's teeth per module; 0: default
  double body_size_per_module = 0;   ///< largest in-plane size per module; 0: default
  double grading = 0;                ///< growth of the size with distance; 0: default
  double contact_size_um = 0;        ///< in-plane size at the contact [µm]; 0: default
  int sector_teeth = -1;             ///< teeth either side of the loaded ones; -1: default
  int tooth_zone = -1;               ///< teeth either side meshed at the tooth size; -1: default
  bool deck_only = false;            ///< write the deck and stop
  /// The structural influence deck (Fe3dOptions::influence, read at the plane model's joining
  /// depths): its compliance G_ij appended to args.csv, one row per (i, j).
  bool influence = false;
};

/// Runs one case and appends its stations to args.csv. @throws on bad input or a failed run.
int Fe3dCommand(const Fe3dCommandArgs& args);

/// The load per unit width across the face of every 3D case of `csv`.
int Fe3dPlot(const std::string& csv, const std::string& svg, int layers, double refinement,
             const std::string& title);

/// The slice model of the same contact against the 3D contact stations of `csv` at (`layers`,
/// `refinement`): uncoupled strips (40 slices) and, with `influence_csv`, the 3D structure's own
/// kernels (test::StructureKernel of `influence_cases` at `influence_layers`, one slice per
/// layer); writes the figure and prints each station's loads; with `kernel_csv`, writes the first
/// influence case's W there as a scene's coupling table. @throws on bad input or a failed solve.
int Fe3dSlices(const std::string& scene, const std::string& csv, const std::string& svg,
               int layers, double refinement, const std::string& influence_csv,
               int influence_layers, const std::string& influence_refinement,
               const std::vector<std::string>& influence_cases, const std::string& kernel_csv,
               const std::string& title);

/// The 3D structure's kernel W (test::StructureKernel of case `name` at `layers` layers and
/// in-plane `refinement` of `influence_csv`, over its plane-strain row) written to `kernel_csv`
/// as a scene's coupling table (docs/scenes.md, "Face width"); prints W and its row sums.
/// @throws on an incomplete CSV or a W that is not positive definite.
int Fe3dKernel(const std::string& influence_csv, const std::string& name, int layers,
               const std::string& refinement, const std::string& kernel_csv);

/// The helical pair's slices (test::HelicalSlicesAt at `angle_deg`, a position of a
/// `positions`-position sweep) against the 3D stations of the cases `names` of `csv`: prints each
/// station's loads (the runs at every discretisation, the slices' station means) and draws the
/// load per unit length of contact line across the face (the runs at `layers` stations as
/// markers, the slices as a line). @throws on bad input or a failed solve.
int Fe3dHelical(const std::string& scene, const std::string& csv, const std::string& svg,
                const std::vector<std::string>& names, double angle_deg, int positions, int layers,
                const std::string& title);

}  // namespace epicycle::fe_reference
