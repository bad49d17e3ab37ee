// NLopt back ends for builds without NLopt (EPICYCLE_WITH_NLOPT=OFF): the classes exist, report
// themselves unavailable, and a Run() returns a failed result without touching the problem.
#include <string>

#include "backend.hpp"

namespace epicycle::solvers::internal {
namespace {

class NloptUnavailable final : public BackendImpl {
 public:
  bool available() const override { return false; }
  BackendResult Run(const ScaledProblem& problem, const ContactOptions&, const Eigen::VectorXd*,
                    const Eigen::VectorXd*) override {
    BackendResult result;
    result.force = Eigen::VectorXd::Zero(problem.num_contacts());
    result.failed = true;
    result.code = -1;
    result.message = "nlopt back ends compiled out (configure with -DEPICYCLE_WITH_NLOPT=ON)";
    return result;
  }
};

}  // namespace

std::unique_ptr<BackendImpl> MakeNloptBackend(Backend which) {
  if (which != Backend::kNloptSlsqp && which != Backend::kNloptLbfgs &&
      which != Backend::kNloptAuglag) {
    throw std::invalid_argument(
        "MakeNloptBackend: backend = " + std::to_string(static_cast<int>(which)) +
        " is not an NLopt back end (nlopt-slsqp, nlopt-lbfgs, nlopt-auglag)");
  }
  return std::make_unique<NloptUnavailable>();
}

}  // namespace epicycle::solvers::internal
