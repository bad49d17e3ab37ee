// The integration settings the dynamic drivers of the bindings share.
#include "integration.hpp"

namespace epicycle::python {

// The integration parameters dynamic and speed_sweep share (numpydoc entries).
const char* kIntegrationDoc = R"doc(
integrator : str, default "cvode-bdf"
    "cvode-bdf" or "arkode-erk".
rtol : float, default 1e-6
    Relative tolerance [-].
rate_scale : float or None, default None
    Rate tolerance scale [1/s] (None: the library's default 1e4; 0: the stage's highest
    linearised natural frequency).
contact_tol : float or None, default None
    Contact solve tolerance [-] on the nondimensional residual (None: 1e-10).
max_order : int, default 5
    CVODE's largest BDF order [-].
analytic_jacobian : bool, default True
    The contact sensitivity (False: CVODE's difference quotients).
backend : str, default "newton"
    The contact back end.
cache_dir : str or None, default None
    Influence-table cache (as quasistatic's).
progress : callable or None, default None
    progress(done, total), called as results complete.
raise_on_failure : bool, default True
    Raise ComputationError on a failure (else return the Result).)doc";

// The integration settings of a driver call, as its keyword options give them.
Integration MakeIntegration(const std::string& integrator, double rtol,
                            std::optional<double> rate_scale, std::optional<double> contact_tol,
                            int max_order, bool analytic_jacobian, const std::string& backend) {
  Integration i;
  i.integrator = integrator;
  i.rtol = rtol;
  i.rate_scale = rate_scale;
  i.contact_tol = contact_tol;
  i.max_order = max_order;
  i.analytic_jacobian = analytic_jacobian;
  i.backend = backend;
  return i;
}

}  // namespace epicycle::python
