#include "epicycle/compliance/compliance_operator.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

namespace epicycle::compliance {

namespace {

// A contact side resolved once: its flank position on the body and its direction in the body
// frame, so the N² loop only interpolates.
struct Located {
  int body = -1;
  InfluenceTable::Node node;  // flank position and interpolation stencil
  Eigen::Vector2d direction;  // body frame
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
  const int n = static_cast<int>(contacts.size());
  std::vector<std::array<Located, 2>> loc(static_cast<std::size_t>(n));
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
      const Eigen::Rotation2Dd to_body(-body.rotation);
      Located& l = loc[j][s];
      l.body = side.body;
      l.direction = to_body * side.direction;
      FlankPosition position;
      double distance = 0;
      const Eigen::Vector2d point = to_body * (side.point - body.centre);
      if (!body.table->TryLocate(point, side.tooth, side.flank, &position, &distance)) {
        try {
          body.table->Locate(point, side.tooth, side.flank);  // throws the table's message
        } catch (const std::invalid_argument& e) {
          throw std::invalid_argument(where() + " on body '" + body.name + "': " + e.what());
        }
      }
      l.node = body.table->Prepare(position);
    }
  }
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < n; ++j) {
    for (int k = j; k < n; ++k) {
      double sum = 0.0;
      for (const Located& a : loc[j]) {
        for (const Located& b : loc[k]) {
          if (a.body != b.body) continue;
          const OperatorBody& body = bodies[a.body];
          sum += a.direction.dot(body.table->PreparedInfluence(b.node, a.node) * b.direction);
          if (!body.support.isZero(0.0)) {
            // The support acts on the centre in the inertial frame: rotate the directions back.
            const Eigen::Rotation2Dd to_world(body.rotation);
            sum += (to_world * a.direction).dot(body.support * (to_world * b.direction));
          }
        }
      }
      c(j, k) = sum;
      c(k, j) = sum;
    }
  }
  return c;
}

}  // namespace epicycle::compliance
