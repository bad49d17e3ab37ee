// Slices of the face width of one gear pair (pair_face_width.hpp; docs/model.md §10).
#include "epicycle/transmission/pair_face_width.hpp"

#include <stdexcept>
#include <string>

namespace epicycle::transmission {

PairFaceWidth::PairFaceWidth(const FaceWidthSpec& spec, const geometry::GearPair& pair)
    : slices_(spec.slices), width_(geometry::ContactFaceWidth(pair.gear1(), pair.gear2())) {
  if (!spec.pin_tilts.empty() || spec.carrier_torsional_stiffness > 0)
    throw std::invalid_argument(
        "face width of a gear pair: pin tilts and the carrier's wind-up belong to a stage");
  if (!active()) return;
  const geometry::Gear* gears[2] = {&pair.gear1(), &pair.gear2()};
  for (int g = 0; g < 2; ++g) lead_[g].width = gears[g]->spec().face_width;
  for (const LeadSpec& l : spec.leads) {
    if (l.gear != "gear1" && l.gear != "gear2")
      throw std::invalid_argument(l.where + ".gear = \"" + l.gear +
                                  "\": a gear pair has gear1 and gear2");
    const int g = l.gear == "gear1" ? 0 : 1;
    GearLead& lead = lead_[g];
    lead.slope = l.slope / (lead.width * gears[g]->base_radius());
    lead.crowning = l.crowning;
    lead.end_relief = l.end_relief;
    lead.end_relief_length = l.end_relief_length;
  }
  coupling_ = spec.coupling == FaceCoupling::kTable
                  ? spec.coupling_table
                  : FaceCouplingMatrix(slices_, width_, spec.coupling, spec.coupling_length);
}

double PairFaceWidth::GapChange(const geometry::PotentialContact& p, int s) const {
  const double z = SliceCentre(s, slices_, width_);
  const GearLead& a = lead_[0];
  const GearLead& b = lead_[1];
  return -z * (p.lever_a * a.slope + p.lever_b * b.slope) -
         LeadRemoved(a.crowning, a.end_relief, a.end_relief_length, a.width, z) -
         LeadRemoved(b.crowning, b.end_relief, b.end_relief_length, b.width, z);
}

void PairFaceWidth::Expand(std::vector<geometry::PotentialContact>* contacts,
                           Eigen::MatrixXd* compliance) const {
  const int n = static_cast<int>(contacts->size()), S = slices_;
  std::vector<geometry::PotentialContact> out;
  out.reserve(static_cast<std::size_t>(n * S));
  for (const geometry::PotentialContact& c : *contacts) {
    for (int s = 0; s < S; ++s) {
      out.push_back(c);
      out.back().overlap = c.overlap + GapChange(c, s);
    }
  }
  Eigen::MatrixXd c(n * S, n * S);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) c.block(j * S, k * S, S, S) = (*compliance)(j, k) * coupling_;
  *compliance = std::move(c);
  *contacts = std::move(out);
}

MeshFaceLoad PairFaceWidth::Loads(const Eigen::VectorXd& force) const {
  std::vector<int> slice(static_cast<std::size_t>(force.size()));
  for (std::size_t j = 0; j < slice.size(); ++j) slice[j] = static_cast<int>(j) % slices_;
  return Loads(force, slice);
}

MeshFaceLoad PairFaceWidth::Loads(const Eigen::VectorXd& force,
                                  const std::vector<int>& slice) const {
  if (slice.size() != static_cast<std::size_t>(force.size()))
    throw std::invalid_argument("PairFaceWidth::Loads: " + std::to_string(slice.size()) +
                                " slice indices for " + std::to_string(force.size()) + " forces");
  MeshFaceLoad f;
  f.line_load.assign(static_cast<std::size_t>(slices_), 0.0);
  const double dz = width_ / slices_;
  for (Eigen::Index j = 0; j < force.size(); ++j)
    f.line_load[static_cast<std::size_t>(slice[static_cast<std::size_t>(j)])] += force(j) / dz;
  SummariseLineLoad(width_, &f);
  return f;
}

}  // namespace epicycle::transmission
