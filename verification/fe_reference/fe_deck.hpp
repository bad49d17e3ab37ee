// An independent full-FE contact reference for the hybrid mesh-stiffness model
// (docs/fe_reference.md): the two gears of a pair at one mesh position, meshed by gmsh from the
// exact generated profile (never through compliance/'s mappers), second-order elements refined at
// the contacts, written as a CalculiX input deck; and the reader of CalculiX's results.
//
// The deck (units mm, N, MPa): a one-element-thick slab of 15-node wedges (C3D15, the 6-node
// triangles of the gmsh mesh extruded over the thickness t) with u_z = 0 at every node, which is
// the plane-strain model (the displacement field is independent of z and ε_zz = 0). Gear 1's hub
// circle (an external gear's axis circle) is given the rigid rotation θ about its centre,
//     u = θ e_z × (x − c_1),
// in a sequence of static steps θ_1 < θ_2 < ...; gear 2's hub (an internal gear's outer rim) is
// held: the boundary conditions of the hybrid model's influence tables. The loaded flanks (involute
// and tip round) of every tooth pair in or near contact form one frictionless surface-to-surface
// contact pair each (linear pressure-overclosure penalty), so CalculiX reports each tooth pair's
// normal force. The moment the hub carries, M = Σ (x − c_1) × R over the hub nodes' reactions R,
// is the torque that holds gear 1 at θ; interpolating θ(M) at the scene's torque gives the loaded
// transmission error, the mesh stiffness k = (|T|/r_b1)/(|θ| r_b1) and the tooth pairs' loads at
// that torque, the quantities of transmission/mesh_stiffness.hpp.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "epicycle/compliance/root_crack.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::fe_reference {

/// Mesh sizes of the reference model; `refinement` divides every size (0.7, 1, 1.41, 2 in the
/// convergence study of docs/fe_reference.md).
struct FeMeshOptions {
  double contact_size = 40e-6;     ///< h_c [m], element size within contact_radius of a contact
  double contact_radius = 0.3e-3;  ///< r_0 [m]
  double grading = 0.25;           ///< growth of the size with distance beyond r_0 [-]
  double tooth_size_per_module = 0.25;  ///< on the teeth next to the mesh, per module [-]
  double body_size_per_module = 2.0;    ///< the largest size, away from the mesh, per module [-]
  int tooth_zone = 2;                   ///< teeth either side of the loaded ones meshed finely [-]
  /// h_f on the fillets (root land and fillet, both sides) of the loaded teeth and of the
  /// `fillet_zone` teeth either side, per module [-]: m/40 = ρ_F/15 on the ISO rack's fillet
  double fillet_size_per_module = 0.025;
  int fillet_zone = 1;  ///< teeth either side of the loaded ones whose fillet stress is read [-]
  double refinement = 1.0;      ///< divides every size [-], > 0
  int points_per_segment = 40;  ///< interpolation points of each profile spline [-]
  void Validate() const;        ///< @throws std::invalid_argument naming the field
};

struct FeContactOptions {
  double penalty = 1e8;          ///< K [MPa/mm] of the linear pressure-overclosure law
  double tension = 0.5;          ///< σ_∞ [MPa], CalculiX's tension at large clearance (small)
  double gap_window = 200e-6;    ///< tooth pairs within this rigid gap get a contact pair [m]
  double slave_reach = 1.0e-3;   ///< slave faces within this of the rigid contact points [m]
  double master_reach = 1.5e-3;  ///< master faces likewise [m]
};

/// A root crack in one tooth of gear 1 or 2 (the geometry of compliance::RootCrack, one straight
/// segment), meshed here independently of compliance's cracked mesh: the crack is a straight curve
/// embedded in the gear's gmsh surface (its mouth splits the fillet curve), and every mesh node on
/// it but the tip's is duplicated in the deck, the elements on the σ-flank side of the path taking
/// the copy. The faces are open: no contact between them (docs/model.md §9 "Root crack").
struct FeCrack {
  int gear = 1;                 ///< 1 or 2
  compliance::RootCrack crack;  ///< tooth, side, start_arc [m] and one segment (length, ν)
  double tip_size = 10e-6;      ///< h_tip [m], element size at the tip (divided by refinement)
  double face_size_per_module = 0.025;  ///< h along the crack faces per module (÷ refinement)
  double tip_grading = 0.25;            ///< growth of the size with distance from the tip [-]
};

/// A spall over the whole face width (w = 1): the involute of one flank lowered by `depth`, normal
/// to the flank, between two roll angles; the lowered piece joins the intact flank by straight
/// steps (the sharp edges of transmission::Pit's region).
struct FeSpall {
  int gear = 1;                       ///< 1 or 2 (external gears)
  int tooth = 0, side = 1;            ///< body-frame tooth k and flank σ
  double roll_from = 0, roll_to = 0;  ///< involute roll angles u [rad], roll_from < roll_to
  double depth = 0;                   ///< d [m], > 0
};

/// Damage of the deck's teeth (both optional).
struct FeDamage {
  std::optional<FeCrack> crack;
  std::optional<FeSpall> spall;
};

/// One tooth pair of the deck: its contact pair's slave (gear 1) and master (gear 2) surfaces.
struct FeToothPair {
  int tooth1 = 0, tooth2 = 0;  ///< tooth indices in the body frames (as ToothPairLoad)
  std::string slave, master;   ///< CalculiX surface names (upper case)
  double rigid_gap = 0;        ///< smallest rigid gap of the pair's contacts at the position [m]
};

/// A node on a fillet curve (root land or fillet) whose surface tangential stress is read.
struct FeFilletNode {
  int gear = 1;             ///< 1 or 2
  int tooth = 0, side = 1;  ///< body-frame tooth index and flank side σ = ±1
  int node = 0;             ///< CalculiX id (the slab's z = 0 layer)
  double arc_length = 0;    ///< along the profile from the space centre line [m]
  double tx = 0, ty = 0;    ///< unit surface tangent in the deck's x-y plane [-]
};

/// What the reader needs besides the .dat file.
struct FeDeckInfo {
  double thickness = 1e-3;        ///< t [m] of the slab
  double face_width = 0;          ///< b [m] of the pair (the narrower gear)
  double torque = 0;              ///< T on gear 1 [N·m], for the whole face width
  double base_radius1 = 0;        ///< r_b1 [m]
  double angle = 0;               ///< position: gear-1 rotation from the cycle start [rad]
  std::vector<double> rotations;  ///< θ of each step [rad]
  std::vector<FeToothPair> pairs;
  std::vector<int> hub_nodes;              ///< CalculiX ids of gear 1's hub nodes
  std::vector<double> hub_x, hub_y;        ///< their coordinates relative to c_1 [mm]
  std::vector<FeFilletNode> fillet_nodes;  ///< the nodes of the fillets whose stress is written
  int nodes = 0, elements = 0;             ///< of the 3-D deck
  int nodes_2d = 0, triangles = 0;         ///< of the gmsh mesh
  int straightened = 0;  ///< curved triangles given straight sides (inside out on a small round)
  int crack_nodes = 0;   ///< nodes of the gmsh mesh duplicated on the crack's faces
  void Write(const std::string& path) const;
  /// @throws std::runtime_error naming the file and line that cannot be read.
  static FeDeckInfo Read(const std::string& path);
};

/// Meshes the pair at gear-1 angle `angle` [rad] (the rigid pose of GearPair::Poses) and writes
/// `deck.inp` and `deck.info` into `directory`, one static step per entry of `rotations` [rad].
/// @throws std::invalid_argument for bad options or rotations of mixed or zero sign;
///         std::runtime_error when gmsh fails or a file cannot be written.
FeDeckInfo WriteDeck(const transmission::Scene& scene, const geometry::GearPair& pair,
                     double torque, double angle, const std::vector<double>& rotations,
                     const FeMeshOptions& mesh, const FeContactOptions& contact,
                     const std::string& directory, const FeDamage& damage = {});

/// The spall of the scene's pit on gear "gear1" or "gear2" (a pair scene's [[damage.pit]]), if
/// any. @throws std::invalid_argument for more than one pit or a pit with width_fraction < 1
/// (the slab is plane strain: a partial-width pit needs layers in z).
std::optional<FeSpall> SpallOfScene(const transmission::Scene& scene);

/// s_Fn [m], the root chord between ISO 6336-3's 30° points of a gear (60° internal).
double IsoRootChord(const geometry::Gear& gear);

/// One static step as CalculiX reports it.
struct FeStepResult {
  double time = 0;                 ///< CalculiX's total time at the end of the step [-]
  double rotation = 0;             ///< θ prescribed [rad]
  double moment = 0;               ///< M on gear 1 from its hub reactions, whole face width [N·m]
  std::vector<double> pair_force;  ///< normal force of each tooth pair, whole face width [N]
};

/// The reference at the scene's torque: θ(M) and the pair forces interpolated between the two
/// steps that bracket |T| (log-log in θ(M), linear in the forces; extrapolated from the last two
/// when |T| lies outside, which `extrapolated` reports).
struct FeSample {
  double angle = 0;                ///< [rad]
  std::size_t step = 0;            ///< the first of the two steps interpolated between
  double weight = 0;               ///< u: value = (1 − u) at `step` + u at `step` + 1 [-]
  double rotation = 0;             ///< θ at T [rad]: the loaded transmission error
  double approach = 0;             ///< δ = |θ| r_b1 [m]
  double mesh_stiffness = 0;       ///< k = (|T|/r_b1)/δ [N/m]
  std::vector<double> pair_force;  ///< [N] at T
  double force_sum = 0;            ///< Σ pair forces [N]
  double moment_balance = 0;  ///< |Σ F_j r_b1 − |T|| / |T| at the last step (involute contacts) [-]
  bool extrapolated = false;
};

/// Reads the steps of `<directory>/deck.dat` (CalculiX .dat: the hub reactions of every step's
/// last increment and the contact statistics of every pair).
/// @throws std::runtime_error when the file is missing or lacks a step's block.
std::vector<FeStepResult> ReadSteps(const std::string& directory, const FeDeckInfo& info);
/// @throws std::runtime_error with fewer than two steps or a non-monotonic M(θ).
FeSample Interpolate(const FeDeckInfo& info, const std::vector<FeStepResult>& steps);

/// The fillet stress of one tooth at the scene's torque: the largest tension and the most
/// negative compression of σ_tt over the nodes of both its fillets, and where.
struct FeToothFillet {
  int gear = 1, tooth = 0;
  double tension = 0;  ///< max σ_tt [Pa] (may be < 0 on a tooth without tension)
  int tension_side = 1;
  double tension_arc = 0;  ///< [m] from the space centre line
  double compression = 0;  ///< min σ_tt [Pa]
  int compression_side = 1;
  double compression_arc = 0;  ///< [m]
};

/// σ_tt = tᵀσt at every fillet node of deck.info at the end of every step, from CalculiX's
/// `<directory>/deck.frd` (the nodal stresses of *EL FILE: each element's integration-point
/// stresses extrapolated to its nodes, averaged over the elements sharing the node) [Pa], one
/// vector per step in info.fillet_nodes order.
/// @throws std::runtime_error when the file is missing or lacks a step's stresses or a node.
std::vector<std::vector<double>> ReadFilletStresses(const std::string& directory,
                                                    const FeDeckInfo& info);
/// Per tooth the extremes of σ_tt interpolated linearly in θ between the sample's two steps.
std::vector<FeToothFillet> FilletExtremes(const FeDeckInfo& info, const FeSample& sample,
                                          const std::vector<std::vector<double>>& sigma);

}  // namespace epicycle::fe_reference
