#include "epicycle/compliance/compliance_operator.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include "epicycle/compliance/damaged_influence.hpp"

namespace epicycle::compliance {

namespace {

// A contact side resolved once: its contact, its body, and its flank position with the direction
// of its force in the body frame, so the pair loop only interpolates.
struct Located {
  int contact = 0;
  int body = -1;
  InfluenceTable::DirectedNode node;
};

// Every side of every contact located on its body's flank once (side s of contact j at 2j + s),
// with `first[b + 1]` counting body b's sides; with `only_loaded`, only the contacts j with
// (*only_loaded)(j) > 0. False with the reason in *off_flank (non-null) for a
// point off its flank; thrown when off_flank is null.
bool LocateSides(const std::vector<OperatorBody>& bodies,
                 const std::vector<OperatorContact>& contacts, std::string* off_flank,
                 std::vector<Located>* out, std::vector<int>* first,
                 const Eigen::VectorXd* only_loaded = nullptr) {
  const int nb = static_cast<int>(bodies.size());
  for (int b = 0; b < nb; ++b) {
    if (bodies[b].table == nullptr) {
      throw std::invalid_argument("AssembleCompliance: body " + std::to_string(b) + " ('" +
                                  bodies[b].name + "') has no influence table");
    }
  }
  first->assign(static_cast<std::size_t>(nb) + 1, 0);
  thread_local std::vector<Eigen::Matrix2d> to_body;  // R(−θ_B); kept: no allocation per call
  to_body.resize(static_cast<std::size_t>(nb));
  for (int b = 0; b < nb; ++b)
    to_body[b] = Eigen::Rotation2Dd(-bodies[b].rotation).toRotationMatrix();
  const int n = static_cast<int>(contacts.size());
  std::vector<Located>& loc = *out;
  loc.clear();
  loc.reserve(static_cast<std::size_t>(2 * n));
  for (int j = 0; j < n; ++j) {
    if (only_loaded != nullptr && !((*only_loaded)(j) > 0.0)) continue;
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
          const std::string text = where() + " on body '" + body.name + "': " + e.what();
          if (off_flank == nullptr) throw std::invalid_argument(text);
          *off_flank = text;
          return false;
        }
      }
      loc.push_back({j, side.body, body.table->PrepareDirected(position, r * side.direction)});
      ++(*first)[side.body + 1];
    }
  }
  return true;
}

}  // namespace

Eigen::MatrixXd AssembleCompliance(const std::vector<OperatorBody>& bodies,
                                   const std::vector<OperatorContact>& contacts,
                                   std::string* off_flank) {
  Eigen::MatrixXd c;
  AssembleCompliance(bodies, contacts, &c, off_flank);
  return c;
}

void AssembleCompliance(const std::vector<OperatorBody>& bodies,
                        const std::vector<OperatorContact>& contacts, Eigen::MatrixXd* out,
                        std::string* off_flank) {
  const int nb = static_cast<int>(bodies.size());
  const int n = static_cast<int>(contacts.size());
  // The located sides and their order, kept per thread: the dynamic model assembles C on every
  // evaluation, and the studies' threads share the operator.
  thread_local std::vector<Located> loc;
  thread_local std::vector<int> first;
  thread_local std::vector<int> order;
  if (!LocateSides(bodies, contacts, off_flank, &loc, &first)) {
    out->resize(0, 0);
    return;
  }
  // The sides grouped by body, in contact order within a body (a counting sort): each body's
  // pairs are then one triangle of its sides.
  for (int b = 0; b < nb; ++b) first[b + 1] += first[b];
  order.resize(loc.size());
  for (int i = 0; i < 2 * n; ++i) order[first[loc[i].body]++] = i;
  for (int b = nb; b > 0; --b) first[b] = first[b - 1];  // back to the starts
  first[0] = 0;
  // C_jk = Σ_B d_Bjᵀ Λ_B(p_Bk → p_Bj) d_Bk (+ support): every pair of sides x ≤ y of a body adds
  // its term to C_jk and C_kj, j ≤ k their contacts (the response at j, the load at k).
  Eigen::MatrixXd& c = *out;
  c.setZero(n, n);
  for (int b = 0; b < nb; ++b) {
    const OperatorBody& body = bodies[b];
    const InfluenceTable& table = *body.table;
    const DamagedInfluence* damaged = body.damaged;
    if (damaged != nullptr && damaged->teeth() != table.teeth()) {
      throw std::invalid_argument("AssembleCompliance: body " + std::to_string(b) + " ('" +
                                  body.name + "'): damaged rows of " +
                                  std::to_string(damaged->teeth()) + " teeth on a table of " +
                                  std::to_string(table.teeth()));
    }
    const bool support = !body.support.isZero(0.0);
    // The support acts on the centre in the inertial frame: rotate the directions back.
    const Eigen::Matrix2d to_world =
        support ? Eigen::Rotation2Dd(body.rotation).toRotationMatrix() : Eigen::Matrix2d::Zero();
    auto term = [&](const Located& response, const Located& load) {
      double v = damaged == nullptr ? table.DirectedCompliance(load.node, response.node)
                                    : damaged->DirectedCompliance(table, load.node, response.node);
      if (support) {
        v += (to_world * response.node.direction)
                 .dot(body.support * (to_world * load.node.direction));
      }
      return v;
    };
    const int end = first[b + 1];
    for (int x = first[b]; x < end; ++x) {
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
}

std::vector<FilletStress> FilletStresses(const std::vector<OperatorBody>& bodies,
                                         const std::vector<OperatorContact>& contacts,
                                         const Eigen::VectorXd& force, int neighbours) {
  if (force.size() != static_cast<Eigen::Index>(contacts.size()))
    throw std::invalid_argument("FilletStresses: " + std::to_string(force.size()) + " forces for " +
                                std::to_string(contacts.size()) + " contacts");
  if (neighbours < 0)
    throw std::invalid_argument("FilletStresses: neighbours = " + std::to_string(neighbours) +
                                ": must be >= 0");
  // Only the contacts that carry load are located (a stage's potential contacts include the
  // unloaded flanks and pairs inside the gap window).
  std::vector<Located> loc;
  std::vector<int> first;
  LocateSides(bodies, contacts, nullptr, &loc, &first, &force);
  // Per body its loads, prepared once, and the teeth within `neighbours` of one that carries
  // load, each once (body b's teeth from tooth_start[b] in `wanted`); then the fillets, their
  // values in one block.
  const int nb = static_cast<int>(bodies.size());
  std::vector<InfluenceTable::FilletLoad> loads;
  loads.reserve(loc.size());
  std::vector<std::size_t> load_start(static_cast<std::size_t>(nb) + 1, 0);
  std::vector<char> wanted;
  std::vector<std::size_t> tooth_start(static_cast<std::size_t>(nb) + 1, 0);
  std::size_t fillets = 0, values = 0;
  for (int b = 0; b < nb; ++b) {
    const InfluenceTable& table = *bodies[b].table;
    if (bodies[b].damaged != nullptr)
      throw std::invalid_argument("FilletStresses: body " + std::to_string(b) + " ('" +
                                  bodies[b].name +
                                  "') is damaged (a root crack): its root stresses are not "
                                  "tabulated");
    if (!table.has_fillet_stress())
      throw std::invalid_argument("FilletStresses: body " + std::to_string(b) + " ('" +
                                  bodies[b].name + "') has a table without fillet stresses");
    const int z = table.teeth();
    const std::size_t teeth = tooth_start[b];
    wanted.resize(teeth + static_cast<std::size_t>(z), 0);
    for (const Located& l : loc) {
      if (l.body != b || !(force(l.contact) > 0.0)) continue;
      loads.push_back(table.PrepareFilletLoad(l.node, force(l.contact)));
      for (int d = -neighbours; d <= neighbours; ++d)
        wanted[teeth + static_cast<std::size_t>(((l.node.tooth + d) % z + z) % z)] = 1;
    }
    load_start[b + 1] = loads.size();
    tooth_start[b + 1] = wanted.size();
    for (std::size_t k = teeth; k < wanted.size(); ++k) {
      fillets += wanted[k] ? 2 : 0;
      values += wanted[k] ? 2 * table.fillet_points().size() : 0;
    }
  }
  std::vector<FilletStress> out;
  out.reserve(fillets);
  const std::shared_ptr<double[]> block = std::make_shared<double[]>(values);  // all 0
  double* next = block.get();
  std::vector<InfluenceTable::FilletTarget> targets;
  targets.reserve(fillets);
  for (int b = 0; b < nb; ++b) {
    const InfluenceTable& table = *bodies[b].table;
    const std::size_t points = table.fillet_points().size();
    targets.clear();
    for (std::size_t k = tooth_start[b]; k < tooth_start[b + 1]; ++k) {
      if (!wanted[k]) continue;
      const int tooth = static_cast<int>(k - tooth_start[b]);
      for (int side = 0; side < 2; ++side) {
        out.push_back({b, tooth, side, std::span<const double>(next, points), &table, block});
        targets.push_back({tooth, side, next});
        next += points;
      }
    }
    // Each load on all of the body's fillets: every fillet still adds the loads in their order.
    for (std::size_t q = load_start[b]; q < load_start[b + 1]; ++q)
      table.AddFilletStress(loads[q], targets);
  }
  return out;
}

}  // namespace epicycle::compliance
