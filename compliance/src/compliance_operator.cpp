#include "epicycle/compliance/compliance_operator.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

namespace epicycle::compliance {

namespace {

// A contact side resolved once: its contact, its body, and its flank position with the direction
// of its force in the body frame, so the pair loop only interpolates.
struct Located {
  int contact = 0;
  int body = -1;
  InfluenceTable::DirectedNode node;
};

}  // namespace

Eigen::MatrixXd AssembleCompliance(const std::vector<OperatorBody>& bodies,
                                   const std::vector<OperatorContact>& contacts,
                                   std::string* off_flank) {
  const int nb = static_cast<int>(bodies.size());
  for (int b = 0; b < nb; ++b) {
    if (bodies[b].table == nullptr) {
      throw std::invalid_argument("AssembleCompliance: body " + std::to_string(b) + " ('" +
                                  bodies[b].name + "') has no influence table");
    }
  }
  // Per body: R(−θ_B), inertial to body frame; and where its sides start in the sides grouped by
  // body (a count first, then the offsets; one entry past the last body ends the last group).
  struct Frame {
    Eigen::Matrix2d to_body = Eigen::Matrix2d::Identity();
    int first = 0;
  };
  std::vector<Frame> frame(static_cast<std::size_t>(nb) + 1);
  for (int b = 0; b < nb; ++b)
    frame[b].to_body = Eigen::Rotation2Dd(-bodies[b].rotation).toRotationMatrix();
  const int n = static_cast<int>(contacts.size());
  std::vector<Located> loc;  // side s of contact j at 2j + s
  loc.reserve(static_cast<std::size_t>(2 * n));
  for (int j = 0; j < n; ++j) {
    for (int s = 0; s < 2; ++s) {
      const ContactSide& side = contacts[j].side[s];
      // The message's context, built only when something is wrong (this loop is on the dynamic
      // model's hot path).
      auto where = [&] {
        return "AssembleCompliance: contact " + std::to_string(j) +
               (contacts[j].label.empty() ? "" : " ('" + contacts[j].label + "')") + " side " +
               std::to_string(s);
      };
      if (side.body < 0 || side.body >= nb) {
        throw std::invalid_argument(where() + ": body = " + std::to_string(side.body) +
                                    "; the rule is 0 <= body < " + std::to_string(nb));
      }
      if (!(std::abs(side.direction.norm() - 1.0) <= 1e-9)) {
        throw std::invalid_argument(where() + ": the direction must be a unit vector (norm " +
                                    std::to_string(side.direction.norm()) + ")");
      }
      const OperatorBody& body = bodies[side.body];
      const Eigen::Matrix2d& r = frame[side.body].to_body;
      FlankPosition position;
      double distance = 0;
      const Eigen::Vector2d point = r * (side.point - body.centre);
      if (!body.table->TryLocate(point, side.tooth, side.flank, &position, &distance)) {
        try {
          body.table->Locate(point, side.tooth, side.flank);  // throws the table's message
        } catch (const std::invalid_argument& e) {
          const std::string text = where() + " on body '" + body.name + "': " + e.what();
          if (off_flank == nullptr) throw std::invalid_argument(text);
          *off_flank = text;
          return Eigen::MatrixXd();
        }
      }
      loc.push_back({j, side.body, body.table->PrepareDirected(position, r * side.direction)});
      ++frame[side.body + 1].first;
    }
  }
  // The sides grouped by body, in contact order within a body (a counting sort): each body's
  // pairs are then one triangle of its sides.
  for (int b = 0; b < nb; ++b) frame[b + 1].first += frame[b].first;
  std::vector<int> order(loc.size());
  for (int i = 0; i < 2 * n; ++i) order[frame[loc[i].body].first++] = i;
  for (int b = nb; b > 0; --b) frame[b].first = frame[b - 1].first;  // back to the starts
  frame[0].first = 0;
  // C_jk = Σ_B d_Bjᵀ Λ_B(p_Bk → p_Bj) d_Bk (+ support): every pair of sides x ≤ y of a body adds
  // its term to C_jk and C_kj, j ≤ k their contacts (the response at j, the load at k).
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(n, n);
  for (int b = 0; b < nb; ++b) {
    const OperatorBody& body = bodies[b];
    const InfluenceTable& table = *body.table;
    const bool support = !body.support.isZero(0.0);
    // The support acts on the centre in the inertial frame: rotate the directions back.
    const Eigen::Matrix2d to_world =
        support ? Eigen::Rotation2Dd(body.rotation).toRotationMatrix() : Eigen::Matrix2d::Zero();
    auto term = [&](const Located& response, const Located& load) {
      double v = table.DirectedCompliance(load.node, response.node);
      if (support) {
        v += (to_world * response.node.direction)
                 .dot(body.support * (to_world * load.node.direction));
      }
      return v;
    };
    const int end = frame[b + 1].first;
    for (int x = frame[b].first; x < end; ++x) {
      const Located& a = loc[order[x]];
      for (int y = x; y < end; ++y) {
        const Located& l = loc[order[y]];
        const int j = a.contact, k = l.contact;
        double v = term(a, l);
        if (j == k && x != y) v += term(l, a);  // both sides of one contact on this body
        c(j, k) += v;
        if (j != k) c(k, j) += v;
      }
    }
  }
  return c;
}

}  // namespace epicycle::compliance
