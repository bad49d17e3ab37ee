// The scene's [[damage.pit]] tables and the strips a pit makes of a contact (damage.hpp): values
// read in SI from the keys' units, the region given by radius converted to the involute roll
// angle u = √((r/r_b)² − 1), and the strips of the face width written out by hand.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "epicycle/geometry/gear.hpp"
#include "epicycle/transmission/damage.hpp"
#include "epicycle/transmission/scene.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using transmission::ContactStrip;

TEST_CASE("damage: pits are read from the scene in SI units", "[unit][transmission]") {
  const std::string text = test::SceneText("paper_stage.toml") + R"(
[[damage.pit]]
gear = "planet2"
tooth = 5
flank = "-"
roll_from_deg = 20.0
roll_to_deg = 24.0
width_fraction = 0.4
depth_um = 30.0

[[damage.pit]]
gear = "ring"
tooth = 64
flank = "+"
radius_from_mm = 136.0
radius_to_mm = 137.0
width_fraction = 1
depth_um = 5
)";
  const transmission::Scene s = transmission::ParseScene(text, "pits.toml");
  REQUIRE(s.damage.pits.size() == 2);
  const transmission::Pit& p = s.damage.pits[0];
  CHECK(p.gear == "planet2");
  CHECK(p.tooth == 5);
  CHECK(p.flank == -1);
  CHECK(p.roll_from == Approx(20.0 * std::numbers::pi / 180).epsilon(1e-15));
  CHECK(p.roll_to == Approx(24.0 * std::numbers::pi / 180).epsilon(1e-15));
  CHECK(p.width_fraction == 0.4);
  CHECK(p.depth == Approx(30e-6).epsilon(1e-15));
  const transmission::Pit& q = s.damage.pits[1];
  const double rb = geometry::Gear(s.stage.ring).base_radius();
  CHECK(q.roll_from == Approx(std::sqrt(std::pow(0.136 / rb, 2) - 1)).epsilon(1e-14));
  CHECK(q.roll_to == Approx(std::sqrt(std::pow(0.137 / rb, 2) - 1)).epsilon(1e-14));
  CHECK(q.flank == 1);
  CHECK(s.warnings.empty());
  // Reported with every result (the provenance, the console).
  CHECK(s.damage.Describe().size() == 2);
  CHECK(s.damage.Describe()[0].find("planet2 tooth 5 flank -") != std::string::npos);
}

TEST_CASE("damage: a scene without damage has none", "[unit][transmission]") {
  CHECK(test::PaperScene().damage.empty());
}

TEST_CASE("damage: a pair scene's pits name gear1 or gear2", "[unit][transmission]") {
  const std::string pair = test::SceneText("iso_pair_20_40.toml");
  const std::string pit =
      "\n[[damage.pit]]\ngear = \"gear2\"\ntooth = 39\nflank = \"+\"\nroll_from_deg = 20\n"
      "roll_to_deg = 22\nwidth_fraction = 1\ndepth_um = 10\n";
  const transmission::Scene s = transmission::ParseScene(pair + pit, "pair.toml");
  REQUIRE(s.damage.pits.size() == 1);
  CHECK(s.damage.pits[0].gear == "gear2");
  CHECK(s.damage.pits[0].tooth == 39);
  try {
    transmission::ParseScene(pair + test::Replace(pit, "\"gear2\"", "\"sun\""), "pair.toml");
    FAIL("a sun pit in a pair scene");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(e.what(), Catch::Contains("damage.pit[0].gear = \"sun\"") &&
                             Catch::Contains("must be one of \"gear1\", \"gear2\""));
  }
}

namespace {

geometry::PotentialContact Contact(geometry::ContactKind kind, int tooth_a, int tooth_b,
                                   double roll_a, double roll_b) {
  geometry::PotentialContact c;
  c.kind = kind;
  c.side_a = 1;
  c.side_b = -1;
  c.tooth_a = tooth_a;
  c.tooth_b = tooth_b;
  c.roll_a = roll_a;
  c.roll_b = roll_b;
  return c;
}

transmission::Pit MakePit(const std::string& gear, int tooth, int flank, double w, double d) {
  transmission::Pit p;
  p.gear = gear;
  p.tooth = tooth;
  p.flank = flank;
  p.roll_from = 0.3;
  p.roll_to = 0.4;
  p.width_fraction = w;
  p.depth = d;
  return p;
}

}  // namespace

TEST_CASE("damage: a pit splits the contacts on its region into strips of the face width",
          "[unit][transmission]") {
  using geometry::ContactKind;
  transmission::Damage damage;
  damage.pits.push_back(MakePit("sun", 3, 1, 0.25, 40e-6));
  damage.pits.push_back(MakePit("planet1", 7, -1, 0.6, 10e-6));
  // Bodies as a stage names them: 0 sun, 1 ring, 2 planet1.
  const transmission::DamageModel model(damage, {"sun", "ring", "planet1"});
  std::vector<ContactStrip> s;
  // Sun tooth 3, flank +, roll inside: (0.75, 0) intact then (0.25, 40 µm).
  model.Strips(0, 2, Contact(ContactKind::kInvolute, 3, 0, 0.35, 0.1), &s);
  REQUIRE(s.size() == 2);
  CHECK(s[0].width_fraction == 0.75);
  CHECK(s[0].depth == 0);
  CHECK(s[0].part == 0);
  CHECK(s[1].width_fraction == 0.25);
  CHECK(s[1].depth == 40e-6);
  CHECK(s[1].part == 1);
  // Outside the roll range, another tooth, the sun's own tip round: whole.
  for (const auto& c : {Contact(ContactKind::kInvolute, 3, 0, 0.45, 0.1),
                        Contact(ContactKind::kInvolute, 4, 0, 0.35, 0.1),
                        Contact(ContactKind::kTipRoundA, 3, 0, 0.35, 0.1)}) {
    model.Strips(0, 2, c, &s);
    REQUIRE(s.size() == 1);
    CHECK(s[0].width_fraction == 1);
    CHECK(s[0].depth == 0);
  }
  // The same pit on the other body's side of the contact (planet1 as body 2 on B): the planet's
  // pit, found through B's tooth, flank (−1) and roll; the sun's tip round touches it.
  model.Strips(0, 2, Contact(ContactKind::kTipRoundA, 0, 7, 0.0, 0.32), &s);
  REQUIRE(s.size() == 2);
  CHECK(s[0].width_fraction == Approx(0.4).epsilon(1e-15));
  CHECK(s[1].width_fraction == 0.6);
  CHECK(s[1].depth == 10e-6);
  // Both flanks pitted at one contact, both pits from the same edge of the face:
  // [0, 0.25] both depths, [0.25, 0.6] the planet's, [0.6, 1] intact.
  model.Strips(0, 2, Contact(ContactKind::kInvolute, 3, 7, 0.35, 0.32), &s);
  REQUIRE(s.size() == 3);
  CHECK(s[0].width_fraction == Approx(0.4).epsilon(1e-15));
  CHECK(s[0].depth == 0);
  CHECK(s[1].width_fraction == Approx(0.35).epsilon(1e-15));
  CHECK(s[1].depth == 10e-6);
  CHECK(s[2].width_fraction == 0.25);
  CHECK(s[2].depth == Approx(50e-6).epsilon(1e-15));
  // A full-width pit leaves one strip, the pitted one.
  transmission::Damage full;
  full.pits.push_back(MakePit("ring", 2, -1, 1.0, 5e-6));
  const transmission::DamageModel ring(full, {"sun", "ring", "planet1"});
  geometry::PotentialContact c = Contact(ContactKind::kInvolute, 0, 2, 0.1, 0.35);
  ring.Strips(2, 1, c, &s);
  REQUIRE(s.size() == 1);
  CHECK(s[0].width_fraction == 1);
  CHECK(s[0].depth == 5e-6);
}

TEST_CASE(
    "damage: the split drops strips beyond the gap window and, without local terms, the "
    "pitted strips beside an intact one",
    "[unit][transmission]") {
  using geometry::ContactKind;
  transmission::Damage damage;
  damage.pits.push_back(MakePit("gear1", 0, 1, 0.5, 150e-6));
  const transmission::DamageModel model(damage, {"gear1", "gear2"});
  std::vector<geometry::PotentialContact> contacts{Contact(ContactKind::kInvolute, 0, 0, 0.35, 0),
                                                   Contact(ContactKind::kInvolute, 1, 0, 0.35, 0)};
  contacts[0].overlap = 0;
  std::vector<int> source;
  std::vector<ContactStrip> strips;
  const std::vector<int> a{0, 0}, b{1, 1};
  // 150 µm deep, window 100 µm: the pitted strip's gap (150 µm) is beyond it.
  CHECK(transmission::SplitContacts(model, a, b, contacts, 100e-6, true, &source, &strips));
  CHECK(source == std::vector<int>{0, 1});
  CHECK(strips[0].width_fraction == 0.5);
  // Window 200 µm: kept, after its contact.
  CHECK(transmission::SplitContacts(model, a, b, contacts, 200e-6, true, &source, &strips));
  CHECK(source == std::vector<int>{0, 0, 1});
  // Without local terms only the least deep strip.
  CHECK(transmission::SplitContacts(model, a, b, contacts, 200e-6, false, &source, &strips));
  CHECK(source == std::vector<int>{0, 1});
  // No contact on the region: the identity, nothing split.
  contacts[0].roll_a = 0.5;
  CHECK_FALSE(transmission::SplitContacts(model, a, b, contacts, 200e-6, true, &source, &strips));
  CHECK(source == std::vector<int>{0, 1});
  // C expanded by the sources: rows repeated.
  Eigen::Matrix2d c;
  c << 1, 2, 2, 5;
  const Eigen::MatrixXd e = transmission::ExpandCompliance(c, {0, 0, 1});
  Eigen::Matrix3d expected;
  expected << 1, 1, 2, 1, 1, 2, 2, 2, 5;
  CHECK(e == expected);
}

namespace {

const char* kCrack = R"(
[[damage.crack]]
gear = "sun"
tooth = 4
side = "-"
start_arc_mm = 1.5
depth_mm = 0.8
angle_deg = 50
)";

std::string CrackError(const std::string& crack) {
  try {
    transmission::ParseScene(test::SceneText("paper_stage.toml") + crack, "crack.toml");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST_CASE("damage: a root crack is read from the scene in SI units", "[unit][transmission]") {
  const transmission::Scene s =
      transmission::ParseScene(test::SceneText("paper_stage.toml") + kCrack, "crack.toml");
  REQUIRE(s.damage.cracks.size() == 1);
  const transmission::Crack& c = s.damage.cracks[0];
  CHECK(c.gear == "sun");
  CHECK(c.start == transmission::CrackStart::kArc);
  CHECK(c.crack.tooth == 4);
  CHECK(c.crack.side == -1);
  CHECK(c.crack.start_arc == Approx(1.5e-3).epsilon(1e-15));
  REQUIRE(c.crack.path.size() == 1);
  CHECK(c.crack.path[0].length == Approx(0.8e-3).epsilon(1e-15));
  CHECK(c.crack.path[0].angle == Approx(50.0 * std::numbers::pi / 180).epsilon(1e-15));
  const std::string base = test::SceneText("paper_stage.toml");
  const long line = std::count(base.begin(), base.end(), '\n') + 3;  // kCrack's "gear =" line
  CHECK(c.where == "crack.toml:" + std::to_string(line) + ": damage.crack[0].gear");
  CHECK(s.damage.CrackOn("sun") == &c);
  CHECK(s.damage.CrackOn("planet1") == nullptr);
  REQUIRE(s.damage.Describe().size() == 1);
  CHECK(s.damage.Describe()[0] ==
        "root crack: sun tooth 4 fillet - from fillet arc 1.5 mm, depth 0.8 mm at 50 deg to the "
        "tooth centre line");
  // A polyline, and the starts placed by the body.
  const transmission::Scene p = transmission::ParseScene(
      test::SceneText("paper_stage.toml") +
          "\n[[damage.crack]]\ngear = \"planet2\"\ntooth = 0\nside = \"+\"\nstart = "
          "\"iso_30deg\"\npath = [{length_mm = 0.5, angle_deg = 45}, {length_mm = 0.25, "
          "angle_deg = 80}]\n",
      "poly.toml");
  REQUIRE(p.damage.cracks.size() == 1);
  CHECK(p.damage.cracks[0].start == transmission::CrackStart::kIso30);
  REQUIRE(p.damage.cracks[0].crack.path.size() == 2);
  CHECK(p.damage.cracks[0].crack.depth() == Approx(0.75e-3).epsilon(1e-14));
  CHECK(p.damage.cracks[0].crack.path[1].angle == Approx(80.0 * std::numbers::pi / 180));
}

TEST_CASE("damage: a root crack's bad values name the key, the value and the rule",
          "[unit][transmission]") {
  CHECK_THAT(CrackError(test::Replace(kCrack, "\"sun\"", "\"planet4\"")),
             Catch::Contains("damage.crack[0].gear = \"planet4\"") &&
                 Catch::Contains("\"planet3\", \"ring\""));
  CHECK_THAT(CrackError(std::string(kCrack) + test::Replace(kCrack, "tooth = 4", "tooth = 9")),
             Catch::Contains("damage.crack[1].gear = \"sun\"") &&
                 Catch::Contains("already has the crack of crack.toml:") &&
                 Catch::Contains("one root crack per gear"));
  CHECK_THAT(CrackError(test::Replace(kCrack, "tooth = 4", "tooth = 16")),
             Catch::Contains("damage.crack[0].tooth = 16") && Catch::Contains("[0, 15]"));
  CHECK_THAT(CrackError(test::Replace(kCrack, "side = \"-\"", "side = \"left\"")),
             Catch::Contains("damage.crack[0].side"));
  CHECK_THAT(
      CrackError(test::Replace(kCrack, "start_arc_mm = 1.5", "start_arc_mm = 40")),
      Catch::Contains("damage.crack[0].start_arc_mm = 40") && Catch::Contains("on the fillet"));
  CHECK_THAT(
      CrackError(test::Replace(kCrack, "start_arc_mm = 1.5",
                               "start_arc_mm = 1.5\nstart = "
                               "\"iso_30deg\"")),
      Catch::Contains("damage.crack[0].start = \"iso_30deg\"") && Catch::Contains("not both"));
  CHECK_THAT(CrackError(test::Replace(kCrack, "angle_deg = 50", "angle_deg = 180")),
             Catch::Contains("damage.crack[0].angle_deg = 180") && Catch::Contains("(0, 180)"));
  CHECK_THAT(CrackError(test::Replace(kCrack, "depth_mm = 0.8", "depth_mm = -1")),
             Catch::Contains("damage.crack[0].depth_mm = -1"));
  // Through the tooth: the path leaves its body sector (named by the crack's own rule).
  CHECK_THAT(CrackError(test::Replace(kCrack, "depth_mm = 0.8", "depth_mm = 30")),
             Catch::Contains("damage.crack[0].depth_mm = 30 mm") &&
                 Catch::Contains("must stay inside its tooth"));
  CHECK_THAT(CrackError(std::string(kCrack) + "path = [{length_mm = 1, angle_deg = 45}]\n"),
             Catch::Contains("damage.crack[0].path") && Catch::Contains("not both"));
  CHECK_THAT(CrackError(test::Replace(kCrack, "depth_mm = 0.8\nangle_deg = 50",
                                      "path = [{length_mm = 1, angle_deg = 45, width = 2}]")),
             Catch::Contains("width"));
}
