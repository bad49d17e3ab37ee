#include "epicycle/dynamics/simulation.hpp"

#include <Eigen/Eigenvalues>

#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <stdexcept>

#include "epicycle/transmission/face_width.hpp"
#include "epicycle/transmission/load_sharing.hpp"

namespace epicycle::dynamics {

std::string IntegratorName(Integrator integrator) {
  return integrator == Integrator::kCvodeBdf ? "cvode-bdf" : "arkode-erk";
}

Integrator IntegratorFromName(const std::string& name) {
  if (name == "cvode-bdf") return Integrator::kCvodeBdf;
  if (name == "arkode-erk") return Integrator::kArkodeErk;
  throw std::invalid_argument("integrator = '" + name + "': not one of cvode-bdf, arkode-erk");
}

void SimulationOptions::Validate() const {
  auto fail = [](const std::string& field, double v, const std::string& rule) {
    throw std::invalid_argument("simulation: " + field + " = " + std::to_string(v) + ": " + rule);
  };
  if (!(rtol > 0 && rtol <= 0.1)) fail("rtol", rtol, "must lie in (0, 0.1]");
  if (!(atol_length > 0) || !std::isfinite(atol_length))
    fail("atol_length", atol_length, "must be > 0");
  if (!(atol_angle > 0) || !std::isfinite(atol_angle))
    fail("atol_angle", atol_angle, "must be > 0");
  if (!(rate_scale >= 0) || !std::isfinite(rate_scale))
    fail("rate_scale", rate_scale, "must be >= 0 (0: the highest natural frequency at t = 0)");
  if (!(atol_energy > 0) || !std::isfinite(atol_energy))
    fail("atol_energy", atol_energy, "must be > 0");
  if (max_steps < 1) fail("max_steps", static_cast<double>(max_steps), "must be >= 1");
  if (!(max_step >= 0) || !std::isfinite(max_step)) fail("max_step", max_step, "must be >= 0");
  if (!(initial_step >= 0) || !std::isfinite(initial_step))
    fail("initial_step", initial_step, "must be >= 0 (0: the integrator's own estimate)");
  if (!(time_limit >= 0) || !std::isfinite(time_limit))
    fail("time_limit", time_limit, "must be >= 0 and finite");
  if (max_order < 1 || max_order > 5) fail("max_order", max_order, "must lie in 1..5");
  if (!(nonlinear_convergence > 0 && nonlinear_convergence <= 1))
    fail("nonlinear_convergence", nonlinear_convergence, "must lie in (0, 1]");
  contact.Validate();
}

namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a) {
  return std::chrono::duration<double>(Clock::now() - a).count();
}

// Everything the C callbacks need; exceptions are caught, stored and rethrown after the
// integrator returns (docs/dynamic.md, "Integration").
struct Context {
  const DynamicModel* model = nullptr;
  std::unique_ptr<solvers::ContactSolver> solver;
  solvers::ContactOptions contact;
  Evaluation warm, scratch;  // last successful evaluation (the warm start), work space
  Eigen::VectorXd d, v;      // the state of the evaluation (reused)
  // Where `warm` was evaluated: the Jacobian at that very state (CVODE's Newton set-up follows
  // its right-hand side at the predicted state) reads it instead of solving the contacts again.
  double warm_t = 0;
  Eigen::VectorXd warm_y;
  bool warm_valid = false;
  SimulationStats* stats = nullptr;
  std::exception_ptr error;
  std::string last_failure;
  bool last_failure_geometry = false;  // the last failed evaluation: poses (true) or contact solve
  bool timed_out = false;              // the time limit was spent
  std::string integrator_message;  // SUNDIALS' own error message (instead of stderr)
  int n = 0;                       // DOFs
  bool limited = false;            // SimulationOptions::time_limit > 0
  Clock::time_point deadline;
};

// SUNDIALS prints its errors to stderr by default; they belong in the run's message.
void ErrorHandler(int code, const char* module, const char* function, char* message, void* user) {
  auto& c = *static_cast<Context*>(user);
  c.integrator_message =
      std::string(module) + " " + function + " (" + std::to_string(code) + "): " + message;
}

// Why the integrator stopped: a right-hand side it could not step around is the last failed
// evaluation's cause (its contact solve or its poses); any other flag is the integrator's own.
transmission::RunStatus StopStatus(int flag, const Context& c) {
  const bool rhs = flag == CV_RHSFUNC_FAIL || flag == CV_REPTD_RHSFUNC_ERR ||
                   flag == CV_UNREC_RHSFUNC_ERR || flag == CV_FIRST_RHSFUNC_ERR ||
                   flag == ARK_RHSFUNC_FAIL || flag == ARK_UNREC_RHSFUNC_ERR ||
                   flag == ARK_REPTD_RHSFUNC_ERR || flag == ARK_FIRST_RHSFUNC_ERR;
  if (rhs && !c.last_failure.empty())
    return c.last_failure_geometry ? transmission::RunStatus::kGeometry
                                   : transmission::RunStatus::kContactFailure;
  return transmission::RunStatus::kIntegratorFailure;
}

void Split(const Context& c, const double* y, Eigen::VectorXd* d, Eigen::VectorXd* v) {
  *d = Eigen::Map<const Eigen::VectorXd>(y, c.n);
  *v = Eigen::Map<const Eigen::VectorXd>(y + c.n, c.n);
}

// One evaluation at (t, y) into c.scratch; false (counted, remembered) if the stage model could
// not evaluate the poses or the contact solve failed.
bool EvaluateAt(Context& c, double t, N_Vector y, Eigen::VectorXd* d, Eigen::VectorXd* v,
                const char* what) {
  Split(c, N_VGetArrayPointer(y), d, v);
  c.model->Evaluate(t, *d, *v, *c.solver, c.contact, &c.warm, &c.scratch, /*energies=*/false);
  ++c.stats->rhs_evaluations;
  if (c.scratch.ok) return true;
  c.last_failure_geometry = !c.scratch.geometry.ok();
  ++(c.last_failure_geometry ? c.stats->failed_geometry : c.stats->failed_solves);
  c.last_failure = "t = " + std::to_string(t) + " s" + what + ": " + c.scratch.message;
  return false;
}

int Rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto& c = *static_cast<Context*>(user);
  try {
    const auto t0 = Clock::now();
    if (c.limited && t0 > c.deadline) {
      c.timed_out = true;
      throw std::runtime_error(
          "the time limit of the run is spent (SimulationOptions::time_limit)");
    }
    const bool ok = EvaluateAt(c, t, y, &c.d, &c.v, "");
    c.stats->rhs_seconds += Seconds(t0);
    if (!ok) return 1;  // recoverable: a smaller step
    double* out = N_VGetArrayPointer(ydot);
    for (int k = 0; k < c.n; ++k) {
      out[k] = c.v(k);
      out[c.n + k] = c.scratch.acceleration(k);
    }
    out[2 * c.n] = c.scratch.external_power;
    out[2 * c.n + 1] = c.scratch.dissipated_power;
    out[2 * c.n + 2] = c.scratch.contact_power;
    std::swap(c.warm, c.scratch);
    // The search's tip-round reuse stays with the work space of the next evaluation: its poses
    // are this one's neighbours (fewer refreshes than keeping one per Evaluation).
    std::swap(c.warm.work.tip_rounds, c.scratch.work.tip_rounds);
    c.warm_t = t;
    c.warm_y = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(y), 2 * c.n);
    c.warm_valid = true;
    return 0;
  } catch (...) {
    c.error = std::current_exception();
    return -1;
  }
}

int Jac(sunrealtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix jac, void* user, N_Vector, N_Vector,
        N_Vector) {
  auto& c = *static_cast<Context*>(user);
  try {
    const auto t0 = Clock::now();
    // The contact solution at this state: CVODE has usually just evaluated it (the last
    // successful evaluation, at the same t and y bit for bit); otherwise solved again here.
    const Evaluation* at = &c.warm;
    if (c.warm_valid && t == c.warm_t &&
        c.warm_y == Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(y), 2 * c.n)) {
      Split(c, N_VGetArrayPointer(y), &c.d, &c.v);
    } else {
      if (!EvaluateAt(c, t, y, &c.d, &c.v, " (Jacobian)")) return 1;
      at = &c.scratch;
    }
    Eigen::MatrixXd dd, dv;
    c.model->Jacobian(t, c.d, c.v, *at, &dd, &dv);
    SUNMatZero(jac);
    const int n = c.n;
    for (int k = 0; k < n; ++k) SM_ELEMENT_D(jac, k, n + k) = 1.0;
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < n; ++k) {
        SM_ELEMENT_D(jac, n + i, k) = dd(i, k);
        SM_ELEMENT_D(jac, n + i, n + k) = dv(i, k);
      }
    ++c.stats->jacobian_evaluations;
    c.stats->jacobian_seconds += Seconds(t0);
    return 0;
  } catch (...) {
    c.error = std::current_exception();
    return -1;
  }
}

// ω_max [rad/s]: the largest √|λ| of ∂d̈/∂d at the start (the linearised stage's highest natural
// frequency, its mesh stiffnesses those of the starting contacts), so that a rate tolerance
// atol·ω_max weighs a vibration's velocity as its amplitude is weighed. 1e4 rad/s if the start
// has no stiffness (no contacts).
double HighestFrequency(const DynamicModel& model, const Eigen::VectorXd& d,
                        const Eigen::VectorXd& v, const Evaluation& at) {
  if (!at.ok) return 1e4;
  Eigen::MatrixXd dd, dv;
  model.Jacobian(0.0, d, v, at, &dd, &dv);
  if (dd.size() == 0 || !dd.allFinite()) return 1e4;
  const double top =
      Eigen::EigenSolver<Eigen::MatrixXd>(dd, false).eigenvalues().cwiseAbs().maxCoeff();
  return top > 0 && std::isfinite(top) ? std::sqrt(top) : 1e4;
}

// RAII owners of the SUNDIALS objects.
struct Sundials {
  SUNContext ctx = nullptr;
  N_Vector y = nullptr, atol = nullptr, dky = nullptr;
  SUNMatrix a = nullptr;
  SUNLinearSolver ls = nullptr;
  void* cvode = nullptr;
  void* erk = nullptr;
  ~Sundials() {
    if (cvode) CVodeFree(&cvode);
    if (erk) ERKStepFree(&erk);
    if (ls) SUNLinSolFree(ls);
    if (a) SUNMatDestroy(a);
    if (y) N_VDestroy(y);
    if (atol) N_VDestroy(atol);
    if (dky) N_VDestroy(dky);
    if (ctx) SUNContext_Free(&ctx);
  }
};

void Check(int flag, const char* what) {
  if (flag < 0)
    throw std::runtime_error(std::string("SUNDIALS: ") + what + " returned " +
                             std::to_string(flag));
}

// Simulate's input: valid options, an initial state of the model's size, output times > 0 and
// increasing. @throws std::invalid_argument naming the rule broken.
void CheckRun(const DynamicModel& model, const SimulationOptions& options,
              const Eigen::VectorXd& d0, const Eigen::VectorXd& v0,
              const std::vector<double>& output_times) {
  options.Validate();
  const int n = model.size();
  if (d0.size() != n || v0.size() != n)
    throw std::invalid_argument("simulation: the initial state has " + std::to_string(d0.size()) +
                                " and " + std::to_string(v0.size()) + " entries, the model " +
                                std::to_string(n) + " DOFs");
  for (std::size_t k = 0; k < output_times.size(); ++k)
    if (!(output_times[k] > (k == 0 ? 0.0 : output_times[k - 1])))
      throw std::invalid_argument("simulation: output times must be > 0 and increasing (entry " +
                                  std::to_string(k) + ")");
}

// The integrator chosen by `options` on s.y and s.atol, its settings, and for CVODE the dense
// linear solver and the analytic Jacobian; the callbacks' user data is `c`.
void SetUpIntegrator(const SimulationOptions& options, int size, Context* c, Sundials& s) {
  const bool cvode = options.integrator == Integrator::kCvodeBdf;
  if (cvode) {
    s.cvode = CVodeCreate(CV_BDF, s.ctx);
    if (!s.cvode) throw std::runtime_error("SUNDIALS: CVodeCreate failed");
    Check(CVodeInit(s.cvode, Rhs, 0.0, s.y), "CVodeInit");
    Check(CVodeSVtolerances(s.cvode, options.rtol, s.atol), "CVodeSVtolerances");
    Check(CVodeSetUserData(s.cvode, c), "CVodeSetUserData");
    Check(CVodeSetErrHandlerFn(s.cvode, ErrorHandler, c), "CVodeSetErrHandlerFn");
    Check(CVodeSetMaxNumSteps(s.cvode, options.max_steps), "CVodeSetMaxNumSteps");
    if (options.max_step > 0) Check(CVodeSetMaxStep(s.cvode, options.max_step), "CVodeSetMaxStep");
    if (options.initial_step > 0)
      Check(CVodeSetInitStep(s.cvode, options.initial_step), "CVodeSetInitStep");
    // A contact set that changes is a C0 kink: allow CVODE more retries at such a step than its
    // default 10 error-test failures before it gives up.
    Check(CVodeSetMaxErrTestFails(s.cvode, 20), "CVodeSetMaxErrTestFails");
    Check(CVodeSetMaxOrd(s.cvode, options.max_order), "CVodeSetMaxOrd");
    Check(CVodeSetNonlinConvCoef(s.cvode, options.nonlinear_convergence), "CVodeSetNonlinConvCoef");
    Check(CVodeSetStabLimDet(s.cvode, options.stability_limit_detection ? SUNTRUE : SUNFALSE),
          "CVodeSetStabLimDet");
    Check(CVodeSetMaxConvFails(s.cvode, 50), "CVodeSetMaxConvFails");
    s.a = SUNDenseMatrix(size, size, s.ctx);
    s.ls = SUNLinSol_Dense(s.y, s.a, s.ctx);
    if (!s.a || !s.ls) throw std::runtime_error("SUNDIALS: cannot create the dense solver");
    Check(CVodeSetLinearSolver(s.cvode, s.ls, s.a), "CVodeSetLinearSolver");
    if (options.analytic_jacobian) Check(CVodeSetJacFn(s.cvode, Jac), "CVodeSetJacFn");
  } else {
    s.erk = ERKStepCreate(Rhs, 0.0, s.y, s.ctx);
    if (!s.erk) throw std::runtime_error("SUNDIALS: ERKStepCreate failed");
    Check(ERKStepSVtolerances(s.erk, options.rtol, s.atol), "ERKStepSVtolerances");
    Check(ERKStepSetUserData(s.erk, c), "ERKStepSetUserData");
    Check(ERKStepSetErrHandlerFn(s.erk, ErrorHandler, c), "ERKStepSetErrHandlerFn");
    Check(ERKStepSetTableNum(s.erk, ARKODE_DORMAND_PRINCE_7_4_5), "ERKStepSetTableNum");
    Check(ERKStepSetMaxNumSteps(s.erk, options.max_steps), "ERKStepSetMaxNumSteps");
    if (options.max_step > 0)
      Check(ERKStepSetMaxStep(s.erk, options.max_step), "ERKStepSetMaxStep");
    if (options.initial_step > 0)
      Check(ERKStepSetInitStep(s.erk, options.initial_step), "ERKStepSetInitStep");
  }
}

// The integration from the last output (last_t, last_y) to tout, *t where it stopped: the
// integrator's flag. An explicit run whose evaluation failed restarts from the last output with a
// smaller first step, at most 8 times in a row.
int Advance(Sundials& s, bool cvode, Context& c, double tout, double last_t,
            const Eigen::VectorXd& last_y, int* restarts_in_a_row, double* t) {
  const int size = static_cast<int>(last_y.size());
  int flag = 0;
  if (cvode) {
    flag = CVode(s.cvode, tout, s.y, t, CV_NORMAL);
  } else {
    flag = ERKStepEvolve(s.erk, tout, s.y, t, ARK_NORMAL);
    // ERKStep cannot retry a failed evaluation: restart from the last output with a smaller
    // first step.
    while (flag == ARK_RHSFUNC_FAIL || flag == ARK_UNREC_RHSFUNC_ERR) {
      if (c.error) break;
      if (++*restarts_in_a_row > 8) break;
      ++c.stats->restarts;
      double h_last = 0;
      ERKStepGetLastStep(s.erk, &h_last);
      Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(s.y), size) = last_y;
      Check(ERKStepReInit(s.erk, Rhs, last_t, s.y), "ERKStepReInit");
      const double h0 = std::max(std::abs(h_last) * 0.1, 1e-12);
      Check(ERKStepSetInitStep(s.erk, h0), "ERKStepSetInitStep");
      flag = ERKStepEvolve(s.erk, tout, s.y, t, ARK_NORMAL);
    }
    if (flag >= 0) *restarts_in_a_row = 0;
  }
  return flag;
}

// The output at tout: the state, one evaluation there (with energies) and what is derived from
// it (load and force sharing, TE, works, root stresses, face loads). False, with the run's message
// and status in *result, if that evaluation fails.
bool OutputSample(const DynamicModel& model, Context& c, Sundials& s, bool cvode, double tout,
                  double contact_energy0, DynamicSample* out, SimulationResult* result) {
  const int n = c.n;
  const double* y = N_VGetArrayPointer(s.y);
  const int sun = model.Find(MotionDof::kSun, MotionDof::kRotation);
  const int sx = model.Find(MotionDof::kSun, MotionDof::kX);
  DynamicSample& sample = *out;
  sample.time = tout;
  sample.carrier_angle = model.CarrierAngle(tout);
  Split(c, y, &sample.d, &sample.v);
  model.Evaluate(tout, sample.d, sample.v, *c.solver, c.contact, &c.warm, &sample.evaluation);
  sample.evaluation.work = {};  // a stored sample keeps the results, not the buffers
  if (!sample.evaluation.ok) {
    result->message = "the output evaluation at t = " + std::to_string(tout) +
                      " s failed: " + sample.evaluation.message;
    result->status = sample.evaluation.geometry.ok() ? transmission::RunStatus::kContactFailure
                                                     : transmission::RunStatus::kGeometry;
    return false;
  }
  const Evaluation& e = sample.evaluation;
  // LSR_i = T_mesh(P_i–S)/T_input: the input torque is the sun's (or its drive's reaction).
  sample.load_sharing = transmission::LoadSharingRatios(e.sun_mesh_torque, e.input_torque);
  sample.force_sharing.assign(sample.load_sharing.size(), 0.0);
  double sun_mesh_force = 0;
  for (int j = 0; j < e.terms.size(); ++j) {
    const transmission::StageContact& contact = e.terms.contacts[j];
    if (contact.mesh != geometry::MeshKind::kSunPlanet || !(e.total_force(j) > 0)) continue;
    sample.force_sharing[static_cast<std::size_t>(contact.planet)] += e.total_force(j);
    sun_mesh_force += e.total_force(j);
  }
  for (double& share : sample.force_sharing)
    share = sun_mesh_force > 0 ? share / sun_mesh_force : 0.0;
  // TE at the sun; a speed-driven sun keeps its speed, and the lag shows at the carrier.
  const int carrier = model.Find(MotionDof::kCarrier, MotionDof::kRotation);
  sample.transmission_error =
      sun >= 0
          ? sample.d(sun)
          : (carrier >= 0 ? -model.stage_model().stage().sun_ratio() * sample.d(carrier) : 0.0);
  if (sx >= 0) sample.sun_centre = Eigen::Vector2d(sample.d(sx), sample.d(sx + 1));
  Check(cvode ? CVodeGetDky(s.cvode, tout, 1, s.dky) : ERKStepGetDky(s.erk, tout, 1, s.dky),
        "GetDky");
  sample.sun_acceleration = sun >= 0 ? N_VGetArrayPointer(s.dky)[n + sun] : 0.0;
  const double planets = static_cast<double>(sample.load_sharing.size());
  for (double lsr : sample.load_sharing)
    sample.k_gamma = std::max(sample.k_gamma, planets * lsr);
  if (sun >= 0) {
    double mesh_torque = 0;
    for (double torque : e.sun_mesh_torque) mesh_torque += torque;
    sample.sun_torque_balance =
        mesh_torque + e.input_torque - model.mass()(sun) * sample.sun_acceleration;
  }
  sample.external_work = y[2 * n];
  sample.dissipated_work = y[2 * n + 1];
  sample.compliance_work = e.contact_energy - contact_energy0 - y[2 * n + 2];
  const transmission::StageCompliance& compliance = model.stage_model().compliance();
  if (compliance.has_root_stress()) {
    // With friction the friction forces load the teeth too.
    transmission::TangentialLoads rubbing;
    const bool rubs = e.friction_tangent.size() == e.terms.contacts.size();
    if (rubs) rubbing = {e.friction, e.friction_tangent};
    // With slices of the face width: each slice's stresses at its own line load.
    sample.fillet_stress = transmission::StateFilletStresses(
        compliance, model.stage_model().stage(), e.poses, e.terms.contacts, e.total_force,
        rubs ? &rubbing : nullptr);
    if (!sample.fillet_stress.empty())
      sample.root_stress = transmission::SummariseRootStress(
          sample.fillet_stress, transmission::PlanetBody(model.stage_model().planets()));
  }
  if (model.stage_model().face_width().active())
    sample.face_loads = transmission::FaceLoads(model.stage_model().stage(),
                                                model.stage_model().face_width().slices(),
                                                e.terms.contacts, e.total_force);
  if (model.stage_model().helical())
    sample.helical = transmission::HelicalLoadsOf(model.stage_model().stage(), e.poses,
                                                  e.terms.contacts, e.total_force);
  return true;
}

// The integrator's counters into *stats.
void ReadCounters(const Sundials& s, bool cvode, SimulationStats* stats) {
  long v = 0;
  if (cvode) {
    CVodeGetNumSteps(s.cvode, &v);
    stats->steps = v;
    CVodeGetNumErrTestFails(s.cvode, &v);
    stats->error_test_failures = v;
    CVodeGetNumNonlinSolvConvFails(s.cvode, &v);
    stats->nonlinear_failures = v;
    CVodeGetNumLinRhsEvals(s.cvode, &v);
    stats->fd_rhs_evaluations = v;
  } else {
    ERKStepGetNumSteps(s.erk, &v);
    stats->steps += v;
    ERKStepGetNumErrTestFails(s.erk, &v);
    stats->error_test_failures = v;
  }
}

}  // namespace

SimulationResult Simulate(const DynamicModel& model, const SimulationOptions& options,
                          const Eigen::VectorXd& d0, const Eigen::VectorXd& v0,
                          const std::vector<double>& output_times,
                          const std::function<void(const DynamicSample&)>& on_sample) {
  CheckRun(model, options, d0, v0, output_times);
  const int n = model.size();
  const auto start = Clock::now();
  SimulationResult result;
  Context c;
  c.model = &model;
  c.solver = solvers::MakeContactSolver(options.backend);
  c.contact = options.contact;
  c.stats = &result.stats;
  c.n = n;
  c.limited = options.time_limit > 0;
  c.deadline = start + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(options.time_limit));

  Sundials s;
  Check(SUNContext_Create(nullptr, &s.ctx), "SUNContext_Create");
  // The deviations, their rates, and three works: W_ext, W_diss and the elastic contact forces'.
  const int size = 2 * n + 3;
  s.y = N_VNew_Serial(size, s.ctx);
  s.atol = N_VNew_Serial(size, s.ctx);
  s.dky = N_VNew_Serial(size, s.ctx);
  if (!s.y || !s.atol || !s.dky) throw std::runtime_error("SUNDIALS: cannot allocate vectors");
  // The warm start of the first evaluation: the state itself, solved cold.
  model.Evaluate(0.0, d0, v0, *c.solver, c.contact, nullptr, &c.warm, /*energies=*/true);
  const double contact_energy0 = c.warm.contact_energy;
  result.stats.rate_scale =
      options.rate_scale > 0 ? options.rate_scale : HighestFrequency(model, d0, v0, c.warm);

  double* y = N_VGetArrayPointer(s.y);
  double* atol = N_VGetArrayPointer(s.atol);
  for (int k = 0; k < n; ++k) {
    const double a =
        model.dofs()[k].axis == MotionDof::kRotation ? options.atol_angle : options.atol_length;
    y[k] = d0(k);
    y[n + k] = v0(k);
    atol[k] = a;
    atol[n + k] = a * result.stats.rate_scale;
  }
  y[2 * n] = y[2 * n + 1] = y[2 * n + 2] = 0.0;
  atol[2 * n] = atol[2 * n + 1] = atol[2 * n + 2] = options.atol_energy;

  const bool cvode = options.integrator == Integrator::kCvodeBdf;
  SetUpIntegrator(options, size, &c, s);

  Eigen::VectorXd last_y = Eigen::Map<Eigen::VectorXd>(y, size);
  double last_t = 0.0;
  std::exception_ptr sink_error;  // thrown by on_sample: rethrown once the integrator is freed
  int restarts_in_a_row = 0;
  try {
    for (std::size_t k = 0; k < output_times.size(); ++k) {
      const double tout = output_times[k];
      double t = last_t;
      const int flag = Advance(s, cvode, c, tout, last_t, last_y, &restarts_in_a_row, &t);
      if (c.error) std::rethrow_exception(c.error);
      if (flag < 0) {
        result.message =
            "stopped at t = " + std::to_string(t) + " s before the output at " +
            std::to_string(tout) +
            " s: " + (cvode ? CVodeGetReturnFlagName(flag) : ERKStepGetReturnFlagName(flag)) +
            (c.last_failure.empty() ? "" : "; last failed evaluation " + c.last_failure);
        result.status = StopStatus(flag, c);
        break;
      }
      DynamicSample sample;
      if (!OutputSample(model, c, s, cvode, tout, contact_energy0, &sample, &result)) break;
      if (on_sample) {
        try {
          on_sample(sample);
        } catch (...) {
          // The sink failed (a result file that cannot be written): not a numerical outcome of
          // the run; its own exception, naming where it happened, goes to the caller.
          sink_error = std::current_exception();
          break;
        }
      }
      ++result.outputs;
      if (options.keep_samples) result.samples.push_back(std::move(sample));
      last_y = Eigen::Map<Eigen::VectorXd>(y, size);
      last_t = tout;
    }
    if (static_cast<std::size_t>(result.outputs) == output_times.size())
      result.status = transmission::RunStatus::kCompleted;
  } catch (const std::exception& ex) {
    // The time limit; an evaluation that threw (its contact solve or compliance: the model's
    // failure, not the integrator's); else the integrator's own set-up or step.
    result.status = c.timed_out ? transmission::RunStatus::kTimeLimit
                    : c.error   ? transmission::RunStatus::kContactFailure
                                : transmission::RunStatus::kIntegratorFailure;
    result.message = "stopped after t = " + std::to_string(last_t) + " s: " + ex.what() +
                     (c.last_failure.empty() ? "" : "; last failed evaluation " + c.last_failure);
  }
  ReadCounters(s, cvode, &result.stats);
  result.stats.wall_seconds = Seconds(start);
  if (sink_error) std::rethrow_exception(sink_error);
  return result;
}

}  // namespace epicycle::dynamics
