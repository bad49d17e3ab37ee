// The integration settings the dynamic drivers of the bindings share (dynamic.cpp, modes.cpp,
// speed_sweep.cpp, periodic_branch.cpp).
#pragma once
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "common.hpp"
#include "epicycle/dynamics/dynamic_run.hpp"
#include "epicycle/dynamics/run_arguments.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "scene.hpp"

namespace epicycle::python {

using ScenePtr = std::shared_ptr<Scene>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A dynamic run's request as the library defaults it: the one statement of the defaults the
// program's options start from, and of the keyword defaults of dynamic, speed_sweep and
// periodic_branch.
inline const dynamics::DynamicRequest& DynamicDefaults() {
  static const dynamics::DynamicRequest defaults;
  return defaults;
}

// The integrator and contact settings of a run (SimulationOptions), each number by its option's
// rule (dynamics/run_arguments.hpp), then by Validate; by default the request's.
struct Integration {
  std::string integrator = DynamicDefaults().integrator;
  double rtol = DynamicDefaults().rtol;
  std::optional<double> rate_scale = DynamicDefaults().rate_scale,
                        contact_tol = DynamicDefaults().contact_tolerance;
  int max_order = DynamicDefaults().max_order;
  bool analytic_jacobian = DynamicDefaults().analytic_jacobian;
  std::string backend = DynamicDefaults().backend;
  dynamics::SimulationOptions Options() const {
    dynamics::CheckArgument(dynamics::DynamicArguments::kRtol, rtol);
    if (rate_scale) dynamics::CheckArgument(dynamics::DynamicArguments::kRateScale, *rate_scale);
    if (contact_tol) dynamics::CheckArgument(dynamics::DynamicArguments::kContactTol, *contact_tol);
    dynamics::CheckArgument(dynamics::DynamicArguments::kMaxOrder, max_order);
    dynamics::SimulationOptions o;
    o.integrator = dynamics::IntegratorFromName(integrator);
    o.backend = BackendOf(backend);
    o.rtol = rtol;
    if (rate_scale) o.rate_scale = *rate_scale;
    if (contact_tol) o.contact.tolerance = *contact_tol;
    o.analytic_jacobian = analytic_jacobian;
    o.max_order = max_order;
    o.Validate();
    return o;
  }
  // The same settings as a run's request (the library resolves and checks them).
  void Apply(dynamics::DynamicRequest* request) const {
    request->integrator = integrator;
    request->rtol = rtol;
    request->rate_scale = rate_scale;
    request->contact_tolerance = contact_tol;
    request->max_order = max_order;
    request->analytic_jacobian = analytic_jacobian;
    request->backend = backend;
  }
};

// The integration parameters dynamic and speed_sweep share (numpydoc entries).
extern const char* kIntegrationDoc;

// The integration settings of a driver call, as its keyword options give them.
Integration MakeIntegration(const std::string& integrator, double rtol,
                            std::optional<double> rate_scale, std::optional<double> contact_tol,
                            int max_order, bool analytic_jacobian, const std::string& backend);

}  // namespace epicycle::python
