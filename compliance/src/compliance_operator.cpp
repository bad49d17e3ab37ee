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
                                   const std::vector<OperatorContact>& contacts) {
  const int nb = static_cast<int>(bodies.size());
  for (int b = 0; b < nb; ++b) {
    if (bodies[b].table == nullptr) {
      throw std::invalid_argument("AssembleCompliance: body " + std::to_string(b) + " ('" +
                                  bodies[b].name + "') has no influence table");
    }
  }
  // R(−θ_B), inertial to body frame, once per body.
  std::vector<Eigen::Matrix2d> to_body(static_cast<std::size_t>(nb));
  for (int b = 0; b < nb; ++b)
    to_body[b] = Eigen::Rotation2Dd(-bodies[b].rotation).toRotationMatrix();
  const int n = static_cast<int>(contacts.size());
  std::vector<Located> loc(static_cast<std::size_t>(2 * n));    // side s of contact j at 2j + s
  std::vector<int> first(static_cast<std::size_t>(nb) + 1, 0);  // sides per body, then offsets
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
      const Eigen::Matrix2d& r = to_body[side.body];
      FlankPosition position;
      double distance = 0;
      const Eigen::Vector2d point = r * (side.point - body.centre);
      if (!body.table->TryLocate(point, side.tooth, side.flank, &position, &distance)) {
        try {
          body.table->Locate(point, side.tooth, side.flank);  // throws the table's message
        } catch (const std::invalid_argument& e) {
          throw std::invalid_argument(where() + " on body '" + body.name + "': " + e.what());
        }
      }
      Located& l = loc[2 * j + s];
      l.contact = j;
      l.body = side.body;
      l.node = body.table->PrepareDirected(position, r * side.direction);
      ++first[side.body + 1];
    }
  }
  // The sides grouped by body, in contact order within a body (a counting sort): each body's
  // pairs are then one triangle of its sides.
  for (int b = 0; b < nb; ++b) first[b + 1] += first[b];
  std::vector<int> order(loc.size());
  {
    std::vector<int> next(first.begin(), first.end() - 1);
    for (int i = 0; i < 2 * n; ++i) order[next[loc[i].body]++] = i;
  }
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
    for (int x = first[b]; x < first[b + 1]; ++x) {
      const Located& a = loc[order[x]];
      for (int y = x; y < first[b + 1]; ++y) {
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
