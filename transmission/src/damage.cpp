#include "epicycle/transmission/damage.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "epicycle/geometry/gear.hpp"

namespace epicycle::transmission {

std::string Pit::Describe() const {
  std::ostringstream o;
  o.precision(6);
  o << gear << " tooth " << tooth << " flank " << (flank > 0 ? "+" : "-") << " roll "
    << geometry::Deg(roll_from) << ".." << geometry::Deg(roll_to) << " deg, width fraction "
    << width_fraction << ", depth " << depth * 1e6 << " um";
  return o.str();
}

std::string Crack::Describe() const {
  std::ostringstream o;
  o.precision(6);
  o << gear << " tooth " << crack.tooth << " fillet " << (crack.side > 0 ? "+" : "-") << " from ";
  if (start == CrackStart::kLargestTension) {
    o << "the largest root tension";
  } else if (start == CrackStart::kIso30) {
    o << "ISO 6336-3's 30-degree point";
  } else {
    o << "fillet arc " << crack.start_arc * 1e3 << " mm";
  }
  o << ", depth " << crack.depth() * 1e3 << " mm";
  if (crack.path.size() == 1) {
    o << " at " << geometry::Deg(crack.path[0].angle) << " deg to the tooth centre line";
  } else {
    o << " (" << crack.path.size() << " segments)";
  }
  return o.str();
}

const Crack* Damage::CrackOn(const std::string& gear) const {
  for (const Crack& c : cracks)
    if (c.gear == gear) return &c;
  return nullptr;
}

std::vector<std::string> Damage::Describe() const {
  std::vector<std::string> out;
  for (const Pit& p : pits) out.push_back("pit: " + p.Describe());
  for (const Crack& c : cracks) out.push_back("root crack: " + c.Describe());
  return out;
}

DamageModel::DamageModel(const Damage& damage, const std::vector<std::string>& bodies) {
  for (const Pit& p : damage.pits) {
    const auto it = std::find(bodies.begin(), bodies.end(), p.gear);
    if (it != bodies.end()) pits_.push_back({static_cast<int>(it - bodies.begin()), p});
  }
}

void DamageModel::FlankPits(int body_a, int body_b, const geometry::PotentialContact& c,
                            double w[2], double d[2]) const {
  w[0] = w[1] = d[0] = d[1] = 0;
  // The pit (w, d) on each flank at the contact point, if any (the scene refuses overlapping pits
  // on one flank, so there is at most one per flank).
  for (const Resolved& r : pits_) {
    for (int which = 0; which < 2; ++which) {
      const bool own_round = c.kind == (which == 0 ? geometry::ContactKind::kTipRoundA
                                                   : geometry::ContactKind::kTipRoundB);
      if (own_round || r.body != (which == 0 ? body_a : body_b)) continue;
      const int tooth = which == 0 ? c.tooth_a : c.tooth_b;
      const int side = which == 0 ? c.side_a : c.side_b;
      const double roll = which == 0 ? c.roll_a : c.roll_b;
      if (tooth != r.pit.tooth || side != r.pit.flank) continue;
      if (!(roll >= r.pit.roll_from && roll <= r.pit.roll_to)) continue;
      w[which] = r.pit.width_fraction;
      d[which] = r.pit.depth;
    }
  }
}

double DamageModel::DepthAt(int body_a, int body_b, const geometry::PotentialContact& c,
                            double fraction) const {
  if (pits_.empty()) return 0;
  double w[2], d[2];
  FlankPits(body_a, body_b, c, w, d);
  return (fraction < w[0] ? d[0] : 0.0) + (fraction < w[1] ? d[1] : 0.0);
}

void DamageModel::Strips(int body_a, int body_b, const geometry::PotentialContact& c,
                         std::vector<ContactStrip>* out) const {
  out->assign(1, ContactStrip{});
  if (pits_.empty()) return;
  double w[2], d[2];
  FlankPits(body_a, body_b, c, w, d);
  if (w[0] == 0 && w[1] == 0) return;
  // Both pits measured from the same edge of the face: strips between the breakpoints.
  const double lo = std::min(w[0], w[1]), hi = std::max(w[0], w[1]);
  const double d_wide = w[0] >= w[1] ? d[0] : d[1];
  out->clear();
  auto add = [&](double width, double depth) {
    if (width > 0) out->push_back({width, depth, 0});
  };
  add(1.0 - hi, 0.0);
  add(hi - lo, d_wide);
  add(lo, d[0] + d[1]);
  std::stable_sort(out->begin(), out->end(),
                   [](const ContactStrip& a, const ContactStrip& b) { return a.depth < b.depth; });
  for (std::size_t k = 0; k < out->size(); ++k) (*out)[k].part = static_cast<int>(k);
}

bool SplitContacts(const DamageModel& damage, const std::vector<int>& body_a,
                   const std::vector<int>& body_b,
                   const std::vector<geometry::PotentialContact>& contacts, double gap_window,
                   bool local_terms, std::vector<int>* source, std::vector<ContactStrip>* strips) {
  const int n = static_cast<int>(contacts.size());
  source->clear();
  strips->clear();
  bool split = false;
  std::vector<ContactStrip> s;
  for (int j = 0; j < n; ++j) {
    damage.Strips(body_a[j], body_b[j], contacts[j], &s);
    if (s.size() != 1 || s[0].depth != 0) split = true;
    // Without local terms the strips differ only by their gaps: the least deep one carries.
    if (!local_terms) s.resize(1);
    for (const ContactStrip& k : s) {
      if (k.depth > 0 && contacts[j].overlap - k.depth < -gap_window) continue;
      source->push_back(j);
      strips->push_back(k);
    }
  }
  if (!split) {
    source->resize(n);
    for (int j = 0; j < n; ++j) (*source)[j] = j;
    strips->assign(n, ContactStrip{});
  }
  return split;
}

Eigen::MatrixXd ExpandCompliance(const Eigen::MatrixXd& compliance,
                                 const std::vector<int>& source) {
  const int n = static_cast<int>(source.size());
  Eigen::MatrixXd out(n, n);
  for (int t = 0; t < n; ++t)
    for (int s = 0; s < n; ++s) out(s, t) = compliance(source[s], source[t]);
  return out;
}

}  // namespace epicycle::transmission
