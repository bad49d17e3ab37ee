#include "epicycle/dynamics/run_tolerances.hpp"

namespace epicycle::dynamics {

RunTolerances TolerancesOf(const SimulationOptions& o, const std::string& backend) {
  return {o.rtol, o.atol_length, o.atol_angle, o.rate_scale, o.contact.tolerance, backend};
}

void VisitTolerances(const RunTolerances& t, transmission::RecordVisitor& visit) {
  visit.Number("rtol", t.rtol);
  visit.Number("atol_length_m", t.atol_length);
  visit.Number("atol_angle_rad", t.atol_angle);
  visit.Number("rate_tolerance_scale_rad_per_s", t.rate_scale);
  visit.Number("contact_tolerance", t.contact_tolerance);
  visit.Text("backend", t.backend);
}

}  // namespace epicycle::dynamics
