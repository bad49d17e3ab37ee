// The warm start's carry-over of forces between two searches (transmission::CarryForces): on the
// paper's stage, with its run-out case's pitch errors, over neighbouring carrier angles where
// contacts enter and leave the gap window, against a match by label (what StageContact::Label()
// names, built independently of SameAs), also with face-width slices and in reversed order; and
// that a search names each potential contact once, which makes the match unique.
#include <catch2/catch.hpp>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "epicycle/transmission/stage_problem.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;

namespace {

// Every contact of `contacts` repeated as slices 0 … S − 1 of the face width (as SplitContacts
// numbers them).
std::vector<transmission::StageContact> Sliced(const std::vector<transmission::StageContact>& c,
                                               int slices) {
  std::vector<transmission::StageContact> out;
  for (const transmission::StageContact& contact : c)
    for (int s = 0; s < slices; ++s) {
      out.push_back(contact);
      out.back().slice = s;
      out.back().slices = slices;
    }
  return out;
}

// The forces of `from` carried to `to` by label, and how many were matched.
int ByLabel(const std::vector<transmission::StageContact>& from, const Eigen::VectorXd& force,
            const std::vector<transmission::StageContact>& to, Eigen::VectorXd* out) {
  std::map<std::string, double> known;
  for (std::size_t i = 0; i < from.size(); ++i)
    known.emplace(from[i].Label(), force(static_cast<Eigen::Index>(i)));
  *out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(to.size()));
  int matched = 0;
  for (std::size_t j = 0; j < to.size(); ++j) {
    const auto it = known.find(to[j].Label());
    if (it == known.end()) continue;
    (*out)(static_cast<Eigen::Index>(j)) = it->second;
    ++matched;
  }
  return matched;
}

}  // namespace

TEST_CASE("CarryForces matches the contacts of two searches by identity, as their labels do",
          "[unit][transmission]") {
  const transmission::Scene scene = transmission::ParseScene(
      test::SceneText("paper_stage_runout.toml"), "paper_stage_runout.toml");
  const geometry::Stage stage(scene.stage);
  const double window = scene.gap_window;
  // 1/8 of a mesh cycle apart, over two mesh cycles of the carrier: contacts enter and leave
  // between the two searches.
  const double cycle = 2 * geometry::kPi / (stage.ring().teeth());
  int entered_or_left = 0, compared = 0;
  for (int k = 0; k < 16; ++k) {
    const double angle = k * cycle / 8;
    const auto from = transmission::SearchStage(stage, stage.Poses(angle), window);
    const auto to = transmission::SearchStage(stage, stage.Poses(angle + cycle / 8), window);
    // A search names each potential contact once.
    std::set<std::string> labels;
    for (const transmission::StageContact& c : from) labels.insert(c.Label());
    REQUIRE(labels.size() == from.size());
    for (int slices : {1, 3}) {
      const auto a = Sliced(from, slices), b = Sliced(to, slices);
      Eigen::VectorXd force(static_cast<Eigen::Index>(a.size()));
      for (Eigen::Index i = 0; i < force.size(); ++i) force(i) = 1.0 + static_cast<double>(i);
      for (bool reversed : {false, true}) {
        std::vector<transmission::StageContact> target = b;
        if (reversed) target.assign(b.rbegin(), b.rend());
        Eigen::VectorXd carried, expected;
        const int matched = transmission::CarryForces(a, force, target, &carried);
        CHECK(matched == ByLabel(a, force, target, &expected));
        CHECK(carried == expected);
        if (matched != static_cast<int>(target.size()) || a.size() != target.size())
          ++entered_or_left;
        ++compared;
      }
    }
  }
  // The sweep saw the contact set change (or the comparison would test the easy case only).
  CHECK(entered_or_left > 0);
  CHECK(compared == 64);
}
