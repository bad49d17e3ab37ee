// The FE contact reference across the face width (docs/fe_reference.md, "3D reference across the
// face width"): the pair of the plane reference (fe_deck.hpp) extruded over the face width b into
// layers of 15-node wedges, with gear 2's axis turned in the plane of action, so that the load per
// unit width along the face, the face-load factor K_Hβ = max q / mean q (ISO 6336-1) and the
// stiffness per unit width in the middle of the face come from a full 3D contact analysis.
//
// The deck (units mm, N, MPa): each gear a sector of teeth (the loaded ones and `sector_teeth`
// either side, closed along the root circle) down to its hub circle (ring: rim), meshed by gmsh in
// the plane (second-order triangles) and extruded into `layers` layers of C3D15 wedges of equal
// thickness b/N_z; the end faces z = 0 and z = b are free. Gear 1's hub cylinder is turned rigidly
// by θ about its axis (u = θ e_z × (x − c_1), u_z = 0) in static steps θ_1 < θ_2 < ...; gear 2's
// hub cylinder is given the rigid rotation ψ = F_β/b about the axis e_z × n through (c_2, b/2), n
// the unit contact normal of the loaded flank (the line of action, gear 1 → gear 2):
//     u = ψ (z − b/2) n,   u_z = −ψ n·(x − c_2),
// which moves gear 2's flank along the line of action by ψ (z − b/2) and so opens the rigid gap by
//     g(z) = F_β (z/b − 1/2)     (F_β > 0: the z = 0 end closes and carries more).
// Gear 1's loaded flank is one slave surface per layer, each its own frictionless
// surface-to-surface contact pair with gear 2's flank (linear penalty), so CalculiX reports the
// normal force F_l of every axial station; the line load of station l is q_l = F_l/Δz_l.
//
// A helical pair (docs/fe_reference.md, "The helical deck"): every level of the extrusion at z is
// the mid-face section turned by each gear's SectionTurn(z − b/2) (geometry/helical.hpp), so each
// gear's flank is the involute helicoid through the plane mesh's profile; the contact lines cross
// the layers. The tooth pairs are those within the gap window in any section, the fine zone and
// the contact surfaces follow the contact across the face; a layer's force F_l is normal to the
// helicoid and F_l cos β_b its transverse part, so q_l = F_l cos β_b/Δz_l, which is also the
// load per unit length of contact line (F_l over the line's length Δz_l/cos β_b).
#pragma once

#include <string>
#include <vector>

#include "fe_deck.hpp"

namespace epicycle::fe_reference {

/// The plane mesh of the 3D deck, coarser than the plane reference's (a 3D contact analysis on 2
/// shared cores cannot afford its 40 µm): 200 µm within 0.3 mm of the contact, m/2 on the loaded
/// teeth (tooth_zone 0), growing by 0.5 × distance to 4 m, 12 spline points per profile segment.
/// Its error on the stiffness is measured by the plane-strain deck of the same mesh against the
/// plane reference (docs/fe_reference.md).
FeMeshOptions Fe3dDefaultMesh();

enum class AxialSupport { kHubs, kBodyMidPlane, kBody };

struct Fe3dOptions {
  double face_width = 0;    ///< b [m]; 0: the pair's contact face width
  int layers = 10;          ///< N_z wedge layers of thickness b/N_z, one axial station each [-]
  double misalignment = 0;  ///< F_β [m], the rigid gap's change from z = 0 to z = b
  int sector_teeth = 1;     ///< teeth modelled either side of the loaded ones [-]
  /// u_z = 0 at every node: the plane-strain model on the same plane mesh (with one layer the
  /// plane deck; with more, the same field, a check of the layers' contact pairs).
  bool plane_strain = false;
  /// What holds the gears axially (docs/fe_reference.md, "The helical deck"): the hub cylinders
  /// alone (kHubs), or besides them u_z = 0 at every node inside each gear's root circle at the
  /// mid-face level z = b/2 (kBodyMidPlane: the bodies below the teeth cannot bend out of their
  /// plane, they may still shear and contract) or at every level (kBody: no axial motion below
  /// the roots, as the plane model's sections); the teeth are free. With a body held, the deck
  /// prints each gear's axial reaction (node sets AXIAL1, AXIAL2: the hub's and the body's held
  /// nodes).
  AxialSupport axial_support = AxialSupport::kHubs;
  FeMeshOptions mesh = Fe3dDefaultMesh();
  /// The plane reference's contact law; a 60 µm window keeps the one tooth pair of a
  /// single-contact position (the neighbours' rigid gaps are > 100 µm on the ISO pair at 13.5°).
  FeContactOptions contact{1e8, 0.5, 60e-6, 1.0e-3, 1.5e-3};
  /// The structural influence deck instead of the contact deck (docs/fe_reference.md, "The
  /// structural compliance along the face"): no contact, both hub cylinders held (u = 0), one
  /// linear static step per layer l with the force pair ∓F n on the two flanks' nodes nearest the
  /// contact, spread uniformly over layer l (a line load on the station), and each gear's
  /// displacement read at `read_depth` below its loaded node along the normal (the plane model's
  /// joining depth h, docs/model.md §4).
  bool influence = false;
  double read_depth[2] = {0, 0};  ///< h of gear 1 and gear 2 [m], > 0 with `influence`
  /// @throws std::invalid_argument naming the field, its value and the rule.
  void Validate() const;
};

/// Where the influence deck reads a gear's displacement: the 6-node triangle around the point
/// at depth h, its quadratic shape functions' weights there, and each node's CalculiX ids at
/// the extruded levels 0..2 N_z (−1 at the odd, mid-layer levels of a mid-side node).
struct Fe3dReadPoint {
  int gear = 1;                          ///< 1 or 2
  std::vector<double> weight;            ///< per triangle node [-], Σ = 1
  std::vector<bool> corner;              ///< per triangle node
  std::vector<std::vector<int>> levels;  ///< per triangle node, 2 N_z + 1 ids
};

/// What the reader of a 3D deck needs besides CalculiX's .dat file.
struct Fe3dDeckInfo {
  /// Hub nodes, steps, torque, r_b1; one entry of `pairs` per (tooth pair, layer); thickness and
  /// face_width both b (the forces are the whole face's).
  FeDeckInfo deck;
  double misalignment = 0;      ///< F_β [m]
  /// cos β_b [-] (1 for spur gears): a layer's contact force, normal to the helicoid, times it
  /// is its transverse part, the force the slices and the hub's moment see.
  double transverse_factor = 1;
  std::vector<double> z_edges;  ///< layer boundaries from the z = 0 face [m], N_z + 1 values
  std::vector<int> pair_layer;  ///< the layer of each entry of deck.pairs
  /// The influence deck's (Fe3dOptions::influence): the unit normal n (gear 1 → gear 2), the force
  /// F [N] of each step's pair and the two read points.
  double normal_x = 0, normal_y = 0;
  double influence_force = 0;
  std::vector<Fe3dReadPoint> read_points;
  void Write(const std::string& path) const;
  /// @throws std::runtime_error naming the file and the line that cannot be read.
  static Fe3dDeckInfo Read(const std::string& path);
};

/// Meshes the pair at gear-1 angle `angle` [rad] and writes `deck.inp`, `deck.info` and
/// `deck3d.info` into `directory`, one static step per entry of `rotations` [rad].
/// @throws std::invalid_argument for bad options or rotations; std::runtime_error when gmsh fails
/// or a file cannot be written.
Fe3dDeckInfo WriteDeck3d(const transmission::Scene& scene, const geometry::GearPair& pair,
                         double torque, double angle, const std::vector<double>& rotations,
                         const Fe3dOptions& options, const std::string& directory);

/// The load across the face at the scene's torque.
struct Fe3dLineLoad {
  double angle = 0;                   ///< gear-1 position [rad]
  double face_width = 0;              ///< b [m]
  double misalignment = 0;            ///< F_β [m]
  std::vector<double> z_lo, z_hi, z;  ///< each station's ends and centre [m]
  std::vector<double> line_load;      ///< q_l = F_l/Δz_l [N/m]
  double rotation = 0;                ///< θ at T [rad]
  double approach = 0;                ///< δ = |θ| r_b1 [m]
  double total_force = 0;             ///< Σ F_l [N]
  double k_hbeta = 0;                 ///< K_Hβ = max q_l / (Σ F_l / b) [-]
  double peak_z = 0;                  ///< centre of the station with the largest q [m]
  double stiffness_per_width = 0;     ///< (Σ F_l / b)/δ [N/m²]
  /// q at z = b/2 (linear between the station centres) over δ [N/m²]: with F_β = 0 the
  /// stiffness per unit width in the middle of the face.
  double middle_stiffness_per_width = 0;
  double moment_balance = 0;  ///< |Σ F r_b1 − |T|| / |T| at the last step [-]
  bool extrapolated = false;  ///< T outside the steps' moments
  int nodes = 0, elements = 0;
  /// With a body held (Fe3dOptions::axial_support): the axial reaction R_z of gear 1's and gear 2's
  /// held nodes (sets AXIAL1, AXIAL2) at T, between the steps as the line load [N]; 0 otherwise.
  double axial_reaction[2] = {0, 0};
};

/// Reads `<directory>/deck.dat` (every layer's contact force and the hub moment per step) and
/// interpolates to the scene's torque as Interpolate does.
/// @throws std::runtime_error as ReadSteps and Interpolate.
Fe3dLineLoad ReadLineLoad(const std::string& directory, const Fe3dDeckInfo& info);

/// The structural compliance along the face of an influence deck (Fe3dOptions::influence):
/// G_ij [m/N], the approach at station i (the two gears' displacements at depth h along n,
/// gear 2's minus gear 1's, each the mean over layer i) per unit force on station j, from
/// `<directory>/deck.dat` (one step per station). @throws std::runtime_error when a step or a
/// read node is missing.
std::vector<std::vector<double>> ReadInfluence(const std::string& directory,
                                               const Fe3dDeckInfo& info);

/// The approach δ [m] of uncoupled slices of stiffness c′ per unit width [N/m²] under a total
/// force F [N] across b [m] with the gap g(z) = F_β (z/b − 1/2): ∫₀ᵇ c′ (δ − g(z))₊ dz = F. The
/// 3D run's first estimate of its steps.
double SliceApproach(double force, double face_width, double stiffness_per_width,
                     double misalignment);

/// WriteDeck3d, ccx and ReadLineLoad in `directory`. The steps are `step_scales` × the estimate
/// θ = SliceApproach(T/r_b1, b, c′, F_β)/r_b1; when the torque falls outside them, once more
/// around the first run's extrapolated θ.
struct Fe3dRun {
  Fe3dDeckInfo deck;
  Fe3dLineLoad result;
  double cpu_seconds = 0;   ///< ccx's CPU time (children's user + system) [s]
  double wall_seconds = 0;  ///< [s]
  int runs = 0;             ///< ccx runs (1, or 2 when the first missed the torque)
};
/// @param stiffness_per_width c′ of the plane model [N/m²] for the steps' estimate.
/// @param ccx the CalculiX program; `threads` its OMP_NUM_THREADS.
/// @throws std::invalid_argument for bad options; std::runtime_error when ccx fails (its log
/// named).
Fe3dRun RunFe3d(const transmission::Scene& scene, const geometry::GearPair& pair, double torque,
                double angle, double stiffness_per_width, const Fe3dOptions& options,
                const std::string& directory, const std::string& ccx = "ccx", int threads = 1,
                const std::vector<double>& step_scales = {0.94, 1.06});

/// WriteDeck3d of an influence deck (options.influence), ccx and ReadInfluence in `directory`.
struct Fe3dInfluenceRun {
  Fe3dDeckInfo deck;
  std::vector<std::vector<double>> compliance;  ///< G_ij [m/N], N_z × N_z
  double cpu_seconds = 0, wall_seconds = 0;     ///< ccx's [s]
};
/// @throws std::invalid_argument for bad options; std::runtime_error when ccx fails.
Fe3dInfluenceRun RunFe3dInfluence(const transmission::Scene& scene,
                                  const geometry::GearPair& pair, double angle,
                                  const Fe3dOptions& options, const std::string& directory,
                                  const std::string& ccx = "ccx", int threads = 1);

}  // namespace epicycle::fe_reference
