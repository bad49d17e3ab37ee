// Bad input named: each file of verification/data/bad_inputs/ is a scene a new user could write
// (a run-out of 1 m, E = 1e-308 GPa, a ring smaller than the sun, ...). Each must be rejected with
// std::invalid_argument whose message names the key, its value and the rule, or (values legal but
// outside the model's validity) load with a warning that names them. The expected texts are
// written here from the rules of docs/scenes.md, not taken from the code's output. With
// EPICYCLE_FIGURES set the test prints BADINPUT rows, collected by tools/bad_input_table.sh into
// docs/bad_inputs.md.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "epicycle/config.h"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/transmission/scene.hpp"
#include "figures.hpp"
#include "stage_fixtures.hpp"

namespace {

struct Case {
  std::string file;                   // in verification/data/bad_inputs/
  bool warning;                       // a warning (loads), not an error
  std::vector<std::string> expected;  // key with value, rule: every piece must be in the message
};

// The paper stage: m = 4.23 mm, z = 16/24/65, j_n = 150 um. Bounds: m/4 = 1057.5 um,
// face width 0.5 m .. 100 m = 2.115 .. 423 mm, hub >= r/5 = 4.23*16/2/5 = 6.768 mm.
const std::vector<Case> kCases = {
    {"runout_1m.toml",
     false,
     {"errors.runout[0].amplitude_um = 1000000", "must be in [0, 1057.5]",
      "quarter of the module"}},
    {"pin_10m.toml", false, {"errors.pin[0].radial_um = 10000000", "must be in [-1057.5, 1057.5]"}},
    {"negative_backlash.toml",
     false,
     {"fit[0].normal_backlash_um = -5", "must be in [0, 1057.5]", "interference"}},
    {"youngs_1e-308.toml", false, {"material.youngs_modulus_GPa = 1e-308", "must be in [1, 1200]"}},
    {"face_width_25km.toml",
     false,
     {"sun.face_width_mm = 25000000", "must be in [2.115, 423]", "modules"}},
    {"hub_1e-308.toml",
     false,
     {"sun.hub_radius_mm = 1e-308", "must be in [6.768, 33.84]", "reference radius"}},
    {"module_1e30.toml", false, {"sun.module_mm = 1e+30", "must be in [0.05, 100]"}},
    {"planet_module_mismatch.toml",
     false,
     {"planet.module_mm = 4", "must equal sun.module_mm = 4.23"}},
    {"ring_smaller_than_sun.toml",
     false,
     {"ring.teeth = 10", "must be in [60, 68]", "z_sun + 2 z_planet = 64"}},
    {"runout_phase_1e300.toml",
     false,
     {"errors.runout[0].phase_deg = 1e+300", "must be in [-360, 360]", "one turn either way"}},
    // A second error table of a kind for the same gear: refused, naming both tables' lines.
    {"duplicate_runout.toml",
     false,
     {"duplicate_runout.toml:99: errors.runout[1].gear = \"planet1\"",
      "a second [[errors.runout]] for planet1", "duplicate_runout.toml:94: errors.runout[0]"}},
    {"duplicate_pin.toml",
     false,
     {"duplicate_pin.toml:102: errors.pin[1].gear = \"planet2\"",
      "a second [[errors.pin]] for planet2", "duplicate_pin.toml:94: errors.pin[0]"}},
    {"duplicate_thickness.toml",
     false,
     {"duplicate_thickness.toml:98: errors.thickness[1].gear = \"sun\"",
      "a second [[errors.thickness]] for the sun",
      "duplicate_thickness.toml:94: errors.thickness[0]"}},
    // ISO 6336-5's endurance limits (docs/scenes.md): sigma_Flim in [50, 1000] MPa, sigma_Hlim in
    // [100, 2500] MPa; the application factor K_A in [1, 4].
    {"bending_limit_5000.toml",
     false,
     {"material.bending_limit_MPa = 5000", "must be in [50, 1000]", "sigma_Flim"}},
    {"contact_limit_0.toml",
     false,
     {"material.contact_limit_MPa = 0", "must be in [100, 2500]", "sigma_Hlim"}},
    {"application_factor_0.5.toml",
     false,
     {"rating.application_factor = 0.5", "must be in [1, 4]", "application factors"}},
    // Values the geometry derives, named by the key the scene wrote and its line: the sun's tip
    // radius r + (x + 3) m = 33.84 + 3.3 * 4.23 = 47.799 mm past the rack's reach r + x m + h_f0 =
    // 33.84 + 1.269 + 1.15 * 4.23 = 39.9735 mm; a ring 1 mm thicker (inside m/4) whose root
    // rounding no longer fits its narrower space, blamed on the error entry; a planet angle
    // 1e-4 deg off the assembly angle 240 deg, named as the scene writes it.
    {"addendum_3.toml",
     false,
     {"addendum_3.toml:24: sun.addendum_per_module = 3.0 gives sun.tip_radius_mm = 47.799",
      "tool's reach", "39.9735"}},
    {"ring_thickness_1000um.toml",
     false,
     {"ring_thickness_1000um.toml:105: errors.thickness[0] (gear = \"ring\")",
      "builds without the scene's errors", "ring.root_round_radius_mm"}},
    {"planet_angle_240.0001.toml",
     false,
     {"planet_angle_240.0001.toml:74: carrier.planet_angles_deg[2] = 240.0001: ", "not whole",
      "240°"}},
    // The lightest gear the model represents (docs/scenes.md, "Ranges and validity"): 0.98 rho b
    // m^2 = 0.98 * 7850 * 0.025 * 4.23e-3^2 = 3.44e-3 kg, that times r_b^2 for the inertia (planet:
    // r_b = 50.76 cos 25 = 46.00 mm, 7.28e-6 kg m^2).
    {"planet_inertia_1e-30.toml",
     false,
     {"planet_inertia_1e-30.toml:46: planet.inertia_kgm2 = 1e-30",
      "must be 0 (not given) or >= 7.2", "lightest gear the model represents",
      "teeth as massless springs"}},
    {"sun_mass_1e-6.toml",
     false,
     {"sun_mass_1e-6.toml:27: sun.mass_kg = 1e-06", "must be 0 (not given) or >= 0.0034"}},
    // The lubricant's viscosity: where the lubricated friction laws give a coefficient, [0.1, 1e4]
    // mPa s; a warning outside the gear oils they were fitted on, [2, 1000].
    {"viscosity_1e300.toml",
     false,
     {"lubricant.viscosity_mPas = 1e+300", "must be in [0.1, 10000]", "pinned at their bounds"}},
    {"viscosity_1e-300.toml",
     false,
     {"lubricant.viscosity_mPas = 1e-300", "must be in [0.1, 10000]", "overflows"}},
    {"warn_viscosity_5000.toml",
     true,
     {"lubricant.viscosity_mPas = 5000", "outside [2, 1000]", "extrapolated"}},
    {"warn_planet_inertia_8e-6.toml",
     true,
     {"warn_planet_inertia_8e-6.toml:46: planet.inertia_kgm2 = 8e-06",
      "outside [1/100, 100] times the solid steel disc"}},
    // Rack cutters with h_a0 = 1.35 m, ρ = 0.05 m: their tooth is pointed from
    // tan α = (π/4)/1.35, α = 30.19° (30.1898); with the tip round, η_c = π m/2 at
    // α = atan2(π/4, 1.3) − asin(0.05/|(1.3, π/4)|) = 29.25°.
    {"pressure_angle_44.9.toml",
     false,
     {"pressure_angle_44.9.toml:22: sun.pressure_angle_deg = 44.9: too large for the rack cutter",
      "α < 29.25", "at most 30.18"}},
    // Two planets at 0°: named by the later one's angle, with the spacing neighbours need.
    {"planet_angles_coincident.toml",
     false,
     {"planet_angles_coincident.toml:74: carrier.planet_angles_deg[1] = 0: clashes with planet 1 "
      "at 0°",
      "neighbouring planets must be at least"}},
#if EPICYCLE_HAVE_GMSH
    // Cracks the mesher cannot mesh, refused as the scene is read under the key that sets them:
    // 0.5 um at 45° (its shape meshes at 4 times the length), and a path that turns back by 130°.
    {"crack_depth_0.0005mm.toml",
     false,
     {"crack_depth_0.0005mm.toml:122: damage.crack[0].depth_mm = 0.0005 mm: must be a crack the "
      "FE mesher (gmsh) can mesh in its tooth",
      "the same shape meshes at a depth of 0.002 mm (its segments 4 times as long)"}},
    {"crack_hairpin.toml",
     false,
     {"crack_hairpin.toml:122: damage.crack[0].path = 1.5 mm: must be a crack the FE mesher",
      "its sharpest turn, 130 deg between segments 0 and 1"}},
#endif
    // The face width's slices (docs/scenes.md, "Face width"): 1 to 200; a crowning removes
    // material; a variation along the face needs two slices; the gap's change between the
    // mid-plane and an end of a mesh at most half the contact search's window (100 um here): 200
    // um over 25 mm tilts the pin by 8 mrad, 100 um from the mid-plane to an end (|n·t| <= |t|);
    // a lead slope of 150 um turns the +z face against the -z face by 150 um, 75 um from the
    // mid-plane; a carrier of 2e6 N m/rad between plates 25 mm apart under the carrier torque
    // |T_s| (1 + z_r/z_s) = 600 (1 + 65/16) = 3037.5 N m twists by 1.519e-3 rad and tilts each
    // pin at r_c = 86.715 mm by 1.519e-3 * 86.715/25 = 5267.9 urad, 65.8 um over half the face.
    {"face_slices_0.toml", false, {"face_width.slices = 0", "must be in [1, 200]"}},
    {"face_slices_1e6.toml", false, {"face_width.slices = 1000000", "must be in [1, 200]"}},
    {"face_crowning_negative.toml",
     false,
     {"face_width.lead[0].crowning_um = -5", "must be >= 0", "would add material"}},
    {"face_lead_one_slice.toml",
     false,
     {"face_width.lead[0].gear = given with face_width.slices = 1", "needs slices >= 2"}},
    {"face_pin_tilt_200um.toml",
     false,
     {"face_width.pin_tilt[0].planet (radial_um = 0, tangential_um = 200 over 25 mm)",
      "the gap changes by up to 100 um between the mid-plane and an end of the sun-planet2 mesh",
      "more than half the contact search's gap window (contact.gap_window_um = 100)"}},
    {"face_lead_slope_150um.toml",
     false,
     {"face_width.lead[0] (gear = \"sun\", slope_um = 150, crowning_um = 0, end_relief_um = 0)",
      "the gap changes by up to 75 um between the mid-plane and an end of the sun-planet1 mesh",
      "more than half the contact search's gap window (contact.gap_window_um = 100)"}},
    {"face_wind_up_soft.toml",
     false,
     {"face_width.carrier_torsional_stiffness_Nm_per_rad = 2000000", "every pin tilted by 5267.9",
      "under the carrier torque 3037.5 N m", "the gap changes by up to 65.8",
      "between the mid-plane and an end of the sun-planet1 mesh",
      "more than half the contact search's gap window (contact.gap_window_um = 100)"}},
    // A gear pair's slices take the leads of gear1 and gear2; a pin and a carrier are a stage's.
    {"face_pair_pin_tilt.toml",
     false,
     {"face_width.pin_tilt = given in a pair scene", "belong to stage scenes",
      "[[face_width.lead]] slope_um of gear1 or gear2"}},
    // A coupling table (docs/scenes.md, "Face width"): one gear pair's W, S × S for its S slices,
    // symmetric (a compliance); a stage's two mesh kinds each their own, both given.
    {"face_table_stage.toml",
     false,
     {"face_width.coupling_table = given in a stage scene",
      "coupling_table_sun_planet and coupling_table_planet_ring"}},
    {"face_table_stage_missing_ring.toml",
     false,
     {"face_width.coupling = \"table\"", "needs coupling_table_planet_ring",
      "one kernel per mesh kind"}},
    {"face_table_stage_ring_size.toml",
     false,
     {"face_width.coupling_table_planet_ring = \"face_table_asymmetric.csv\"",
      "has no entry (0, 2)", "every pair of the face_width.slices = 10 slices"}},
    {"face_table_pair_stage_key.toml",
     false,
     {"face_width.coupling_table_planet_ring = given in a pair scene",
      "takes its kernel from coupling_table"}},
    {"face_table_size.toml",
     false,
     {"face_width.coupling_table = \"../../../scenes/iso_pair_20_40_structure_kernel.csv\"",
      "line 6 '0,4,", "each row must be i,j,w with 0 <= i, j < face_width.slices = 4"}},
    {"face_table_asymmetric.toml",
     false,
     {"face_width.coupling_table = \"face_table_asymmetric.csv\"", "must be symmetric",
      "|W_ij - W_ji| reaches 0.1"}},
    {"warn_runout_above_backlash.toml",
     true,
     {"errors.runout[0].amplitude_um = 200", "larger than the normal backlash j_n = 150 um"}},
    {"warn_pin_above_backlash.toml",
     true,
     {"errors.pin[0].tangential_um = 300", "larger than the normal backlash j_n = 150 um"}},
    {"warn_contact_ratio_below_1.toml",
     true,
     {"[sun]/[planet]: transverse contact ratio epsilon_alpha = 0.6", "< 1"}},
    // Helical stages (scenes/grc_helical_stage.toml, docs/scenes.md "Helical gears"): the helix
    // angle's magnitude in [0, 45) deg; an external mesh needs opposite hands, an internal one
    // the same hand; a normal module whose transverse module m_n/cos β puts the unshifted
    // centre distance m_t (z_s + z_p)/2 more than 2 m_n from the carrier radius (12 mm:
    // 12/cos 7.5° · 60/2 = 363.1 mm against 302.789 mm).
    {"helix_angle_50.toml",
     false,
     {"helix.helix_angle_deg = 50", "must be in [0, 45)", "the hand gives its direction"}},
    {"helix_angle_-10.toml", false, {"helix.helix_angle_deg = -10", "must be in [0, 45)"}},
    {"hands_external_same.toml",
     false,
     {"hands_external_same.toml:", "planet.hand = \"right\"",
      "an external mesh needs opposite hands"}},
    {"hands_internal_opposite.toml",
     false,
     {"hands_internal_opposite.toml:", "ring.hand = \"right\"",
      "an internal mesh needs the same hand"}},
    {"helix_module_12mm.toml",
     false,
     {"sun.module_mm = 12", "transverse module m_n/cos(beta) = 12.10", "at 363.1",
      "carrier.radius_mm = 302.789", "cannot be assembled"}},
    // A helical pair (scenes/iso_pair_20_40_helical.toml, z 20/40, beta 15 deg): the same rules.
    {"helical_pair_same_hands.toml",
     false,
     {"helical_pair_same_hands.toml:37:", "gear2.hand = \"right\"",
      "an external mesh needs opposite hands"}},
    // m_n = 5 mm: m_t = 5/cos 15° = 5.176 mm, m_t (20 + 40)/2 = 155.29 mm ± 2 m_t.
    {"helical_pair_module_5mm.toml",
     false,
     {"pair.centre_distance_mm = 124.233142", "must be in [144.93",
      "m_t = gear1.module_mm/cos(beta) = 5.176", "module_mm = 5", "helix_angle_deg = 15",
      "(z1 + z2)/2 = 155.29"}},
};

std::string Dir() { return std::string(EPICYCLE_TEST_DATA_DIR) + "/bad_inputs/"; }

// The message of reading the scene and making its stage; "" if both succeed.
std::string ErrorOf(const std::string& path, std::vector<std::string>* warnings) {
  try {
    const auto scene = epicycle::transmission::ReadScene(path);
    if (scene.kind == epicycle::transmission::SceneKind::kStage) {
      const epicycle::geometry::Stage stage = epicycle::transmission::MakeStage(scene);
    } else {
      const epicycle::geometry::GearPair pair = epicycle::transmission::MakePair(scene, scene.pair);
    }
    *warnings = scene.warnings;
    return "";
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

// Whether `text` (not empty) holds every piece (each one CHECKed); `joined`: "a ... b".
bool HasPieces(const std::string& text, const std::vector<std::string>& pieces,
               std::string* joined) {
  bool pass = !text.empty();
  for (const std::string& piece : pieces) {
    CHECK_THAT(text, Catch::Matchers::Contains(piece));
    pass = pass && text.find(piece) != std::string::npos;
    *joined += (joined->empty() ? "" : " ... ") + piece;
  }
  return pass;
}

// `text` without every occurrence of `folder`.
std::string Without(std::string text, const std::string& folder) {
  for (auto p = text.find(folder); p != std::string::npos; p = text.find(folder))
    text.erase(p, folder.size());
  return text;
}

void Row(const std::string& input, const std::string& expected, const std::string& got, bool pass) {
  if (epicycle::test::FiguresWanted())
    std::printf("BADINPUT\x1f%s\x1f%s\x1f%s\x1f%s\n", epicycle::test::Cell(input).c_str(),
                epicycle::test::Cell(expected).c_str(), epicycle::test::Cell(got).c_str(),
                pass ? "pass" : "FAIL");
}

}  // namespace

TEST_CASE("bad scene values are named with key, value and rule, or warned about",
          "[unit][transmission][bad-input]") {
  for (const Case& c : kCases) {
    INFO(c.file);
    std::vector<std::string> warnings;
    const std::string error = ErrorOf(Dir() + c.file, &warnings);
    std::string text = error;
    if (c.warning) {
      CHECK(error.empty());
      text.clear();
      for (const std::string& w : warnings) text += w + "\n";
    }
    std::string expected;
    const bool pass = HasPieces(text, c.expected, &expected);
    // The message quoted without the file's directory (the table is read in docs/).
    std::string shown = Without(text, Dir());
    while (!shown.empty() && shown.back() == '\n') shown.pop_back();
    for (char& ch : shown)
      if (ch == '\n') ch = ' ';
    Row(std::string(c.warning ? "warning: " : "error: ") + "`" + c.file + "`", expected, shown,
        pass);
  }
}

namespace {

// A pit on the paper stage (scenes/paper_stage.toml with one [[damage.pit]] appended): every key
// of the table, each with a bad value. The planet's flank (z = 24, m = 4.23 mm, r_b = 46.004 mm)
// runs from its form circle to its tip round's tangency, roll 12.556..39.067 deg; depths up to
// m/4 = 1057.5 um, warned above 0.05 m = 211.5 um.
struct PitCase {
  std::string name;                   // what is wrong, for the table
  std::string keys;                   // the pit's keys (replacing those of kGoodPit they name)
  bool warning;
  std::vector<std::string> expected;  // every piece must be in the message
};

const char* kGoodPit[] = {"gear = \"planet1\"",  "tooth = 13",          "flank = \"-\"",
                          "roll_from_deg = 23.0", "roll_to_deg = 28.0", "width_fraction = 0.5",
                          "depth_um = 30.0"};

const std::vector<PitCase> kPitCases = {
    {"an unknown gear", "gear = \"planet4\"", false,
     {"damage.pit[0].gear = \"planet4\"", "must be one of \"sun\", \"planet1\", \"planet2\", "
                                          "\"planet3\", \"ring\""}},
    {"a tooth index past z", "tooth = 24", false,
     {"damage.pit[0].tooth = 24", "must be in [0, 23]", "0 <= k < z = 24"}},
    {"a flank that is not + or -", "flank = \"left\"", false,
     {"damage.pit[0].flank = \"left\"", "must be one of"}},
    {"no region", "roll_from_deg = -\nroll_to_deg = -", false,
     {"damage.pit[0].roll_from_deg = missing", "give the region as roll_from_deg and roll_to_deg, "
                                               "or as radius_from_mm and radius_to_mm"}},
    {"both forms of the region", "radius_from_mm = 50.0", false,
     {"damage.pit[0].roll_from_deg = given with radius_from_mm/radius_to_mm", "not both"}},
    {"a roll beyond the involute", "roll_to_deg = 45.0", false,
     {"damage.pit[0].roll_to_deg = 45", "must be in [12.556", "39.066",
      "a pit lowers the involute only"}},
    {"a radius below the form circle",
     "roll_from_deg = -\nroll_to_deg = -\nradius_from_mm = 46.5\nradius_to_mm = 50.0", false,
     {"damage.pit[0].radius_from_mm = 46.5", "must be in [47.09", "55.68",
      "a pit lowers the involute only"}},
    {"an empty region", "roll_to_deg = 20.0", false,
     {"damage.pit[0].roll_to_deg = 20", "must be greater than roll_from_deg"}},
    {"a width fraction of 0", "width_fraction = 0", false,
     {"damage.pit[0].width_fraction = 0", "must be in (0, 1]"}},
    {"a width fraction above 1", "width_fraction = 1.5", false,
     {"damage.pit[0].width_fraction = 1.5", "must be in (0, 1]"}},
    {"a depth of 0", "depth_um = 0", false,
     {"damage.pit[0].depth_um = 0", "must be in (0, 1057.5]", "quarter of the module"}},
    {"a depth of 2 mm", "depth_um = 2000", false,
     {"damage.pit[0].depth_um = 2000", "must be in (0, 1057.5]"}},
    {"an unknown key", "diameter_mm = 1", false, {"damage.pit[0]", "diameter_mm"}},
    {"a deep pit", "depth_um = 300", true,
     {"damage.pit[0].depth_um = 300", "deeper than 211.5 um (5 % of the module)",
      "compliance of the intact tooth"}},
};

// The pit's table: kGoodPit with the keys `keys` names replaced ("key = -" removes one).
std::string PitTable(const std::string& keys) {
  std::vector<std::string> lines(std::begin(kGoodPit), std::end(kGoodPit));
  std::istringstream in(keys);
  for (std::string line; std::getline(in, line);) {
    const std::string key = line.substr(0, line.find(' '));
    bool replaced = false;
    for (std::string& l : lines)
      if (l.substr(0, l.find(' ')) == key) {
        l = line;
        replaced = true;
      }
    if (!replaced) lines.push_back(line);
  }
  std::string table = "\n[[damage.pit]]\n";
  for (const std::string& l : lines)
    if (l.find(" = -") == std::string::npos) table += l + "\n";
  return table;
}

}  // namespace

TEST_CASE("bad pit values are named with key, value and rule, or warned about",
          "[unit][transmission][bad-input]") {
  const std::string stage = epicycle::test::SceneText("paper_stage.toml");
  for (const PitCase& c : kPitCases) {
    INFO(c.name);
    std::string text, error;
    try {
      const auto scene = epicycle::transmission::ParseScene(stage + PitTable(c.keys), "pit.toml");
      for (const std::string& w : scene.warnings) text += w + "\n";
    } catch (const std::invalid_argument& e) {
      error = e.what();
    }
    if (c.warning) {
      CHECK(error.empty());
    } else {
      CHECK(text.empty());
      text = error;
    }
    std::string expected;
    const bool pass = HasPieces(text, c.expected, &expected);
    while (!text.empty() && text.back() == '\n') text.pop_back();
    Row(std::string(c.warning ? "warning: " : "error: ") + "`paper_stage.toml` + pit with " +
            c.name + " (`" + epicycle::test::Replace(c.keys, "\n", "; ") + "`)",
        expected, text, pass);
  }
  // Two pits overlapping on one flank of one tooth: refused, naming both tables.
  const std::string two = stage + PitTable("") + PitTable("roll_from_deg = 27.0\nroll_to_deg = 30.0");
  std::string error;
  try {
    epicycle::transmission::ParseScene(two, "pits.toml");
  } catch (const std::invalid_argument& e) {
    error = e.what();
  }
  std::string expected;
  const bool pass = HasPieces(error,
                              {"damage.pit[1].roll_from_deg = 27", "overlaps the pit of",
                               "damage.pit[0].gear", "give one pit per region"},
                              &expected);
  Row("error: `paper_stage.toml` + two pits overlapping on one flank", expected, error, pass);
  // The same regions on the other flank, or on another planet, are two pits.
  CHECK_NOTHROW(epicycle::transmission::ParseScene(
      stage + PitTable("") + PitTable("flank = \"+\"\nroll_from_deg = 27.0\nroll_to_deg = 30.0"),
      "pits.toml"));
  CHECK_NOTHROW(epicycle::transmission::ParseScene(
      stage + PitTable("") + PitTable("gear = \"planet2\""), "pits.toml"));
}

TEST_CASE("a directory given as an input file is named as a directory",
          "[unit][transmission][bad-input]") {
  const std::string dir = Dir();
  std::string scene_error, problem_error;
  try {
    epicycle::transmission::ReadScene(dir);
  } catch (const std::invalid_argument& e) {
    scene_error = e.what();
  }
  try {
    epicycle::solvers::ReadContactProblemFile(dir);
  } catch (const std::invalid_argument& e) {
    problem_error = e.what();
  }
  const std::string expect_scene = "is a directory, not a scene file";
  const std::string expect_problem = "is a directory, not a problem file";
  CHECK_THAT(scene_error, Catch::Matchers::Contains(expect_scene));
  CHECK_THAT(problem_error, Catch::Matchers::Contains(expect_problem));
  const bool pass = scene_error.find(expect_scene) != std::string::npos &&
                    problem_error.find(expect_problem) != std::string::npos;
  auto shown = [&](std::string m) {
    for (auto p = m.find(dir); p != std::string::npos; p = m.find(dir))
      m.replace(p, dir.size(), "DIR");
    return m;
  };
  Row("a directory as scene file, then as contact problem file",
      expect_scene + " ... " + expect_problem, shown(scene_error) + " / " + shown(problem_error),
      pass);
}

TEST_CASE("an input that is not a regular file, or too large, is refused before it is read",
          "[unit][transmission][bad-input]") {
  // A FIFO without a writer (reading it would block forever), /dev/zero (never ends), a symlink to
  // it, and a scene past the 1 MiB a scene file may have (docs/scenes.md).
  const auto tmp =
      std::filesystem::temp_directory_path() / ("epicycle-special-" + std::to_string(::getpid()));
  std::filesystem::create_directories(tmp);
  const std::string fifo = (tmp / "scene.fifo").string(), link = (tmp / "zero.toml").string(),
                    big = (tmp / "big.toml").string();
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::filesystem::create_symlink("/dev/zero", link);
  {
    std::ofstream out(big);
    out << "# " << std::string((1u << 20) + 10, 'x') << "\n";
  }
  struct Special {
    std::string input, path;
    std::vector<std::string> expected;
    bool problem;  // read as a contact problem file, else as a scene
  };
  const std::vector<Special> cases = {
      {"a FIFO as scene file",
       fifo,
       {"scene.fifo: is a FIFO (named pipe), not a scene file (TOML)"},
       false},
      {"/dev/zero as scene file",
       "/dev/zero",
       {"/dev/zero: is a character device, not a scene file"},
       false},
      {"a symlink to /dev/zero as contact problem file",
       link,
       {"contact problem file", "zero.toml: is a character device, not a problem file (JSON)"},
       true},
      {"a scene of 1 MiB + 13 bytes",
       big,
       {"big.toml: 1048589 bytes: larger than the 1 MiB a scene file (TOML) may have"},
       false},
  };
  for (const Special& c : cases) {
    INFO(c.input);
    std::string error;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      if (c.problem) {
        epicycle::solvers::ReadContactProblemFile(c.path);
      } else {
        epicycle::transmission::ReadScene(c.path);
      }
    } catch (const std::invalid_argument& e) {
      error = e.what();
    }
    CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(5));  // refused, not read
    std::string expected;
    const bool pass = HasPieces(error, c.expected, &expected);
    Row(c.input, expected, Without(error, tmp.string() + "/"), pass);
  }
  std::filesystem::remove_all(tmp);
}

TEST_CASE("every scene of scenes/ loads without warnings", "[unit][transmission]") {
  // The shipped examples are inside the model's validity (paper_stage_runout: 20 um < 150 um).
  for (const auto& e : std::filesystem::directory_iterator(EPICYCLE_SCENES_DIR)) {
    if (e.path().extension() != ".toml") continue;
    INFO(e.path().string());
    const auto scene = epicycle::transmission::ReadScene(e.path().string());
    CHECK(scene.warnings.empty());
    CHECK(scene.hash.rfind("fnv1a64:", 0) == 0);
  }
}

TEST_CASE("ContentHash is the 64-bit FNV-1a hash", "[unit][transmission]") {
  // Published FNV-1a 64 test vectors (Fowler, Noll, Vo): "" and "a".
  CHECK(epicycle::transmission::ContentHash("") == "fnv1a64:cbf29ce484222325");
  CHECK(epicycle::transmission::ContentHash("a") == "fnv1a64:af63dc4c8601ec8c");
}
