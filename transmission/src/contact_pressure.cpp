#include "epicycle/transmission/contact_pressure.hpp"

#include <limits>
#include <stdexcept>

#include "epicycle/geometry/stage.hpp"

namespace epicycle::transmission {

void ContactPressureTracker::Add(const std::vector<StageContact>& contacts,
                                 const std::vector<solvers::LocalTermParameters>& local,
                                 const Eigen::VectorXd& force, double x) {
  if (local.empty()) return;  // a problem without local terms carries no contact curvatures
  if (contacts.size() != local.size() || force.size() != static_cast<Eigen::Index>(local.size()))
    throw std::invalid_argument("ContactPressureTracker: " + std::to_string(contacts.size()) +
                                " contacts, " + std::to_string(local.size()) +
                                " local terms and " + std::to_string(force.size()) +
                                " forces: must be equal");
  for (std::size_t j = 0; j < contacts.size(); ++j) {
    const double f = force(static_cast<Eigen::Index>(j));
    if (!(f > 0)) continue;
    const StageContact& c = contacts[j];
    const double p = solvers::HertzPressure(local[j], f);
    const bool tip = c.contact.kind != geometry::ContactKind::kInvolute;
    for (int which = 0; which < 2; ++which) {
      const int body = which == 0 ? c.body_a : c.body_b;
      FlankPressure& best = flanks_[{body, c.loaded ? 0 : 1, tip ? 1 : 0}];
      if (p <= best.pressure) continue;
      best.body = body;
      best.drive = c.loaded;
      best.pressure = p;
      best.half_width = solvers::HertzHalfWidth(local[j], f);
      const bool own_tip = c.contact.kind == (which == 0 ? geometry::ContactKind::kTipRoundA
                                                          : geometry::ContactKind::kTipRoundB);
      best.roll = own_tip ? std::numeric_limits<double>::quiet_NaN()
                          : (which == 0 ? c.contact.roll_a : c.contact.roll_b);
      best.tooth = which == 0 ? c.contact.tooth_a : c.contact.tooth_b;
      best.mesh = geometry::MeshName(c.planet, c.mesh);
      best.tip = tip;
      best.x = x;
      best.validity_ratio = local[j].enabled ? f / solvers::ValidityLimitForce(local[j]) : 0.0;
    }
  }
}

std::vector<FlankPressure> ContactPressureTracker::Result() const {
  std::vector<FlankPressure> out;
  for (const auto& [key, f] : flanks_) out.push_back(f);
  return out;
}

}  // namespace epicycle::transmission
