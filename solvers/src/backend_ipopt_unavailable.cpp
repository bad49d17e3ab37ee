// Ipopt back end for builds without Ipopt (EPICYCLE_WITH_IPOPT=OFF): the class exists, reports
// itself unavailable, and a Run() returns a failed result without touching the problem.
#include "backend.hpp"

namespace epicycle::solvers::internal {
namespace {

class IpoptUnavailable final : public BackendImpl {
 public:
  bool available() const override { return false; }
  BackendResult Run(const ScaledProblem& problem, const ContactOptions&, const Eigen::VectorXd*,
                    const Eigen::VectorXd*) override {
    BackendResult result;
    result.force = Eigen::VectorXd::Zero(problem.num_contacts());
    result.failed = true;
    result.code = -1;
    result.message = "ipopt back end compiled out (configure with -DEPICYCLE_WITH_IPOPT=ON)";
    return result;
  }
};

}  // namespace

std::unique_ptr<BackendImpl> MakeIpoptBackend() { return std::make_unique<IpoptUnavailable>(); }

}  // namespace epicycle::solvers::internal
