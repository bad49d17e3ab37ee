// NLopt back ends: SLSQP (equalities and bounds), bound-constrained L-BFGS (problems without
// equalities) and AUGLAG_EQ around CCSAQ (equalities by augmented Lagrangian, bounds in CCSAQ).
//
// The program is the driver's nondimensional one (NLopt's stopping tests are relative and its
// internal scalings assume O(1) data: in SI units it stops at wrong answers). With a support
// compliance S, free variables y on the supported rows P = {i : S(i,:) ≠ 0} are added exactly as
// in the Ipopt back end:
//
//   min  Φ(x) + ½ y_Pᵀ S_PP y_P     s.t.  x ≥ 0,   G x + S(:,P) y_P = W.
//
// NLopt returns no multipliers: BackendResult::multiplier stays empty and the driver recovers λ.
// BackendResult::iterations counts objective evaluations (NLopt has no common iteration count).
//
// Two passes. L-BFGS, CCSAQ and SLSQP's line search compare objective values. Φ is O(1) in the
// driver's units, and near the answer a step that lowers the residual to r changes Φ by only ~r²:
// below r ≈ 1e-8 that is under the rounding of Φ itself and the algorithms stop, roundoff-limited
// (measured: L-BFGS and AUGLAG at 1e-9…3e-8). So after the first pass a second one is run from
// its point x_r, on the same function minus the constant Φ(x_r), evaluated as a sum of terms that
// vanish with x − x_r (RecentredObjective), so its rounding is relative to the change. The
// gradient is unchanged. Same algorithm, same stopping rules, the remaining evaluation budget;
// the message names both passes' results. Default on for L-BFGS and AUGLAG, whose floor this is
// (AUGLAG on the closed-form cases: 3e-10 → 1e-12); off for SLSQP, whose steps come from its QP
// and which gained nothing at tight tolerances on the stage-sized problems for 20–50 % more time.
// "nlopt.recentre" = 0 or 1 overrides.
//
// Errors. The C++ API turns NLopt's negative results into exceptions; ROUNDOFF_LIMITED usually
// comes with a usable point, which is returned with its code, not as a failure. Exceptions thrown
// by our own callbacks are caught there, stored, NLopt is stopped (force_stop) and the exception is
// rethrown after optimize() returns.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wconversion"
#include <nlopt.hpp>
#pragma GCC diagnostic pop

#include "backend.hpp"

namespace epicycle::solvers::internal {
namespace {

constexpr char kNamespace[] = "nlopt.";

// Keys accepted as "nlopt.<key>"; all take numbers.
constexpr const char* kKnownOptions[] = {
    "xtol_rel",  // relative step tolerance (default: ContactOptions::tolerance)
    "xtol_abs",  // absolute step tolerance on every variable (default kXtolAbsFactor·tolerance)
    "ftol_rel",  // relative objective-change tolerance (default 0: off)
    "ftol_abs",  // absolute objective-change tolerance (default 0: off)
    "maxeval",   // objective-evaluation budget (default kEvaluationsPerIteration·max_iterations)
    "maxtime",   // [s] (default ContactOptions::time_limit)
    "constraint_tol",  // equality tolerance NLopt uses to call a point feasible (default tolerance)
    "vector_storage",  // L-BFGS memory (default: NLopt's)
    "local_xtol_rel",  // AUGLAG's CCSAQ: relative step tolerance (default: xtol_rel)
    "local_ftol_rel",  // AUGLAG's CCSAQ: relative objective tolerance (default: ftol_rel)
    "local_maxeval",   // AUGLAG's CCSAQ: evaluations per subproblem (default: maxeval)
    "recentre",        // 1: second pass with the objective re-centred; 0: one pass
};

// A force resting on its bound x = 0 never passes a relative step test (|Δx| ≤ xtol_rel·|x| = 0),
// so without an absolute one CCSAQ inside AUGLAG spent its whole budget on the first subproblem
// of a one-contact case that starts at 0. Scaled forces are O(1); 1e-4·tolerance (1e-2 stopped
// AUGLAG early on the raw-SI case of the collection, 1e-4 fixes both).
constexpr double kXtolAbsFactor = 1e-4;

// One SLSQP iteration costs one to a few evaluations, an L-BFGS or CCSAQ iteration one or two;
// max_iterations is given in iterations, NLopt's budget in evaluations.
constexpr int kEvaluationsPerIteration = 50;

[[noreturn]] void ThrowBadOption(const std::string& full_key, const std::string& value,
                                 const std::string& rule) {
  std::ostringstream os;
  os << "ContactOptions.backend_options[\"" << full_key << "\"] = \"" << value << "\": " << rule;
  throw std::invalid_argument(os.str());
}

struct Settings {
  double xtol_rel = 0, xtol_abs = 0, ftol_rel = 0, ftol_abs = 0;
  int maxeval = 0;
  double maxtime = 0, constraint_tol = 0;
  int vector_storage = 0;  // 0: NLopt's default
  double local_xtol_rel = -1, local_ftol_rel = -1;
  int local_maxeval = -1;
  int recentre = -1;  // -1: the back end's default (see the file comment)
};

Settings ReadSettings(const ContactOptions& options) {
  Settings s;
  s.xtol_rel = options.tolerance;
  s.xtol_abs = kXtolAbsFactor * options.tolerance;
  s.maxeval = options.max_iterations > std::numeric_limits<int>::max() / kEvaluationsPerIteration
                  ? std::numeric_limits<int>::max()
                  : kEvaluationsPerIteration * options.max_iterations;
  s.maxtime = options.time_limit;
  s.constraint_tol = options.tolerance;
  for (const auto& [full_key, value] : options.backend_options) {
    if (full_key.rfind(kNamespace, 0) != 0) continue;  // another back end's option
    const std::string key = full_key.substr(sizeof(kNamespace) - 1);
    bool known = false;
    for (const char* k : kKnownOptions) known = known || key == k;
    if (!known) {
      std::string rule = "unknown NLopt option; known:";
      for (const char* k : kKnownOptions) rule += std::string(" ") + k;
      ThrowBadOption(full_key, value, rule);
    }
    const char* begin = value.c_str();
    char* end = nullptr;
    const double number = std::strtod(begin, &end);
    if (value.empty() || end != begin + value.size() || !std::isfinite(number)) {
      ThrowBadOption(full_key, value, "must be a finite number");
    }
    const bool is_count = key == "maxeval" || key == "vector_storage" || key == "local_maxeval";
    if (key == "recentre") {
      if (number != 0 && number != 1) ThrowBadOption(full_key, value, "must be 0 or 1");
    } else if (is_count) {
      if (number != std::floor(number) || number < 1 || number > std::numeric_limits<int>::max()) {
        ThrowBadOption(full_key, value, "must be an integer ≥ 1");
      }
    } else if (key == "maxtime" ? number <= 0 : number < 0) {
      ThrowBadOption(full_key, value, key == "maxtime" ? "must be > 0" : "must be ≥ 0");
    }
    if (key == "xtol_rel") s.xtol_rel = number;
    if (key == "xtol_abs") s.xtol_abs = number;
    if (key == "ftol_rel") s.ftol_rel = number;
    if (key == "ftol_abs") s.ftol_abs = number;
    if (key == "maxeval") s.maxeval = static_cast<int>(number);
    if (key == "maxtime") s.maxtime = number;
    if (key == "constraint_tol") s.constraint_tol = number;
    if (key == "vector_storage") s.vector_storage = static_cast<int>(number);
    if (key == "local_xtol_rel") s.local_xtol_rel = number;
    if (key == "local_ftol_rel") s.local_ftol_rel = number;
    if (key == "local_maxeval") s.local_maxeval = static_cast<int>(number);
    if (key == "recentre") s.recentre = static_cast<int>(number);
  }
  return s;
}

std::string ResultName(int code) {
  switch (code) {
    case nlopt::FAILURE:
      return "FAILURE";
    case nlopt::INVALID_ARGS:
      return "INVALID_ARGS";
    case nlopt::OUT_OF_MEMORY:
      return "OUT_OF_MEMORY";
    case nlopt::ROUNDOFF_LIMITED:
      return "ROUNDOFF_LIMITED";
    case nlopt::FORCED_STOP:
      return "FORCED_STOP";
    case nlopt::SUCCESS:
      return "SUCCESS";
    case nlopt::STOPVAL_REACHED:
      return "STOPVAL_REACHED";
    case nlopt::FTOL_REACHED:
      return "FTOL_REACHED";
    case nlopt::XTOL_REACHED:
      return "XTOL_REACHED";
    case nlopt::MAXEVAL_REACHED:
      return "MAXEVAL_REACHED";
    case nlopt::MAXTIME_REACHED:
      return "MAXTIME_REACHED";
    default:
      return "NLopt result " + std::to_string(code);
  }
}

// Everything the callbacks need; one per Run().
class Program {
 public:
  explicit Program(const ScaledProblem& problem)
      : problem_(problem),
        num_contacts_(problem.num_contacts()),
        num_equalities_(problem.num_equalities()) {
    std::vector<int> supported;
    if (problem.has_support) {
      for (int i = 0; i < num_equalities_; ++i) {
        if (problem.S.row(i).cwiseAbs().maxCoeff() > 0.0) supported.push_back(i);
      }
    }
    num_support_ = static_cast<int>(supported.size());
    support_block_.resize(num_support_, num_support_);
    support_columns_.resize(num_equalities_, num_support_);
    for (int k = 0; k < num_support_; ++k) {
      for (int l = 0; l < num_support_; ++l) {
        support_block_(k, l) = problem.S(supported[k], supported[l]);
      }
      support_columns_.col(k) = problem.S.col(supported[k]);
    }
  }

  int num_variables() const { return num_contacts_ + num_support_; }
  int num_equalities() const { return num_equalities_; }
  int num_contacts() const { return num_contacts_; }
  int evaluations() const { return evaluations_; }
  const std::exception_ptr& error() const { return error_; }
  void set_opt(nlopt::opt* opt) { opt_ = opt; }

  // From now on the objective is Φ(x) − Φ(x_r) (plus the support term's difference), evaluated
  // without cancellation: see RecentredObjective.
  void Recentre(const std::vector<double>& reference) {
    recentred_ = true;
    xr_.resize(num_contacts_);
    yr_.resize(num_support_);
    for (int j = 0; j < num_contacts_; ++j) xr_(j) = std::max(reference[j], 0.0);
    for (int k = 0; k < num_support_; ++k) yr_(k) = reference[num_contacts_ + k];
    linear_r_ = problem_.C * xr_ - problem_.delta0;
    support_r_ = support_block_ * yr_;
  }

  static double Objective(unsigned n, const double* x, double* grad, void* data) {
    auto* self = static_cast<Program*>(data);
    return self->Guard(std::numeric_limits<double>::infinity(), [&] {
      ++self->evaluations_;
      self->Load(n, x);
      double value = 0.0;
      if (self->recentred_) {
        value = self->RecentredObjective();
      } else {
        value = self->problem_.Objective(self->x_);
        if (self->num_support_ > 0) value += 0.5 * self->y_.dot(self->support_block_ * self->y_);
      }
      if (grad != nullptr) {
        self->problem_.Gradient(self->x_, &self->gradient_);
        for (int j = 0; j < self->num_contacts_; ++j) grad[j] = self->gradient_(j);
        if (self->num_support_ > 0) {
          const Eigen::VectorXd sy = self->support_block_ * self->y_;
          for (int k = 0; k < self->num_support_; ++k) grad[self->num_contacts_ + k] = sy(k);
        }
      }
      return value;
    });
  }

  // c(x, y) = G x + S(:,P) y − W = 0; grad is m×n row-major.
  static void Equalities(unsigned m, double* result, unsigned n, const double* x, double* grad,
                         void* data) {
    auto* self = static_cast<Program*>(data);
    self->Guard(0.0, [&] {
      const int nc = self->num_contacts_;
      Eigen::Map<const Eigen::VectorXd> xv(x, nc);
      Eigen::Map<const Eigen::VectorXd> yv(x + nc, self->num_support_);
      Eigen::VectorXd c = self->problem_.G * xv - self->problem_.W;
      if (self->num_support_ > 0) c += self->support_columns_ * yv;
      for (unsigned i = 0; i < m; ++i) result[i] = c(i);
      if (grad != nullptr) {
        for (unsigned i = 0; i < m; ++i) {
          for (int j = 0; j < nc; ++j) grad[i * n + j] = self->problem_.G(i, j);
          for (int k = 0; k < self->num_support_; ++k) {
            grad[i * n + nc + k] = self->support_columns_(i, k);
          }
        }
      }
      return 0.0;
    });
  }

 private:
  // Runs a callback body; an exception is stored, NLopt is asked to stop, and Run rethrows it.
  template <typename Body>
  double Guard(double fallback, Body&& body) {
    try {
      return body();
    } catch (...) {
      if (error_ == nullptr) error_ = std::current_exception();
      if (opt_ != nullptr) opt_->set_force_stop(1);
      return fallback;
    }
  }

  // The algorithms keep x within its bounds; the clamp only removes rounding below zero, where
  // the local term is not defined.
  void Load(unsigned n, const double* x) {
    x_.resize(num_contacts_);
    y_.resize(num_support_);
    for (int j = 0; j < num_contacts_; ++j) x_(j) = std::max(x[j], 0.0);
    for (int k = 0; k < num_support_; ++k) y_(k) = x[num_contacts_ + k];
    (void)n;
  }

  // Φ(x) − Φ(x_r) = ½dᵀCd + (C x_r − δ0)ᵀd + Σ_j [U_j(x_j) − U_j(x_r,j)],  d = x − x_r,
  // with every term small when d is: its rounding is relative to the difference, not to Φ.
  // U_j(x_j) − U_j(x_r,j) = ∫ u_j over [x_r,j, x_j] by 4-point Gauss–Legendre when
  // |d_j| ≤ x_r,j/4 (u_j is smooth there; the error is of order (d_j/x_r,j)⁸ relative); otherwise
  // (x_r,j = 0, where U_j(0) = 0, or a large step, where the difference is large anyway) by
  // difference of the closed-form U_j taken from ScaledProblem::Objective on masked vectors.
  double RecentredObjective() {
    const Eigen::VectorXd d = x_ - xr_;
    double value = 0.5 * d.dot(problem_.C * d) + linear_r_.dot(d);
    if (num_support_ > 0) {
      const Eigen::VectorXd dy = y_ - yr_;
      value += 0.5 * dy.dot(support_block_ * dy) + support_r_.dot(dy);
    }
    if (!problem_.has_local) return value;
    static constexpr double kNode[4] = {-0.8611363115940526, -0.3399810435848563,
                                        0.3399810435848563, 0.8611363115940526};
    static constexpr double kWeight[4] = {0.3478548451374538, 0.6521451548625461,
                                          0.6521451548625461, 0.3478548451374538};
    Eigen::VectorXd direct_x = Eigen::VectorXd::Zero(num_contacts_);
    Eigen::VectorXd direct_r = Eigen::VectorXd::Zero(num_contacts_);
    Eigen::VectorXd mid = xr_ + 0.5 * d;
    Eigen::VectorXd quadrature = Eigen::VectorXd::Zero(num_contacts_);
    bool any_direct = false;
    std::vector<bool> by_quadrature(num_contacts_, false);
    for (int j = 0; j < num_contacts_; ++j) {
      if (xr_(j) > 0.0 && std::abs(d(j)) <= 0.25 * xr_(j)) {
        by_quadrature[j] = true;
      } else {
        direct_x(j) = x_(j);
        direct_r(j) = xr_(j);
        any_direct = any_direct || d(j) != 0.0;
      }
    }
    for (int i = 0; i < 4; ++i) {
      const Eigen::VectorXd node = mid + (0.5 * kNode[i]) * d;
      problem_.LocalValue(node, &local_);
      quadrature += kWeight[i] * local_;
    }
    for (int j = 0; j < num_contacts_; ++j) {
      if (by_quadrature[j]) value += 0.5 * d(j) * quadrature(j);
    }
    if (any_direct) value += LocalIntegral(direct_x) - LocalIntegral(direct_r);
    return value;
  }

  // Σ_j U_j(v_j) = Φ(v) − ½vᵀCv + δ0ᵀv (only used where its rounding does not matter).
  double LocalIntegral(const Eigen::VectorXd& v) const {
    return problem_.Objective(v) - 0.5 * v.dot(problem_.C * v) + problem_.delta0.dot(v);
  }

  const ScaledProblem& problem_;
  int num_contacts_;
  int num_equalities_;
  int num_support_ = 0;
  Eigen::MatrixXd support_block_;    // S_PP
  Eigen::MatrixXd support_columns_;  // S(:,P)
  Eigen::VectorXd x_, y_, gradient_, local_;
  bool recentred_ = false;
  Eigen::VectorXd xr_, yr_, linear_r_, support_r_;
  int evaluations_ = 0;
  nlopt::opt* opt_ = nullptr;
  std::exception_ptr error_;
};

void ApplyStopping(nlopt::opt& opt, double xtol_rel, double ftol_rel, const Settings& s,
                   int maxeval) {
  opt.set_xtol_rel(xtol_rel);
  opt.set_ftol_rel(ftol_rel);
  opt.set_ftol_abs(s.ftol_abs);
  if (s.xtol_abs > 0) opt.set_xtol_abs(s.xtol_abs);
  opt.set_maxeval(maxeval);
  opt.set_maxtime(s.maxtime);
}

class NloptBackend final : public BackendImpl {
 public:
  explicit NloptBackend(Backend which) : which_(which) {}

  bool available() const override { return true; }

  std::vector<std::string> option_keys() const override {
    return std::vector<std::string>(std::begin(kKnownOptions), std::end(kKnownOptions));
  }

  BackendResult Run(const ScaledProblem& problem, const ContactOptions& options,
                    const Eigen::VectorXd* x0, const Eigen::VectorXd*) override {
    const Settings settings = ReadSettings(options);
    const int nc = problem.num_contacts();
    if (x0 != nullptr && x0->size() != nc) {
      throw std::invalid_argument("NLopt back end: warm start x0 has size " +
                                  std::to_string(x0->size()) + ", must equal the " +
                                  std::to_string(nc) + " contacts");
    }
    BackendResult result;
    result.force = Eigen::VectorXd::Zero(nc);
    if (which_ == Backend::kNloptLbfgs && problem.num_equalities() > 0) {
      result.force.resize(0);  // no point at all: the driver must not judge one
      result.failed = true;
      result.code = nlopt::INVALID_ARGS;
      result.message = "nlopt-lbfgs handles only problems without equalities (this one has " +
                       std::to_string(problem.num_equalities()) + ")";
      return result;
    }

    Program program(problem);
    const unsigned n = static_cast<unsigned>(program.num_variables());
    const unsigned m = static_cast<unsigned>(program.num_equalities());
    nlopt::algorithm algorithm = nlopt::LD_SLSQP;
    if (which_ == Backend::kNloptLbfgs) algorithm = nlopt::LD_LBFGS;
    if (which_ == Backend::kNloptAuglag) algorithm = nlopt::AUGLAG_EQ;
    nlopt::opt opt(algorithm, n);
    program.set_opt(&opt);

    std::vector<double> lower(n, -HUGE_VAL);
    for (int j = 0; j < nc; ++j) lower[j] = 0.0;
    opt.set_lower_bounds(lower);
    opt.set_min_objective(&Program::Objective, &program);
    if (m > 0) {
      opt.add_equality_mconstraint(&Program::Equalities, &program,
                                   std::vector<double>(m, settings.constraint_tol));
    }
    ApplyStopping(opt, settings.xtol_rel, settings.ftol_rel, settings, settings.maxeval);
    if (which_ == Backend::kNloptLbfgs && settings.vector_storage > 0) {
      opt.set_vector_storage(static_cast<unsigned>(settings.vector_storage));
    }
    if (which_ == Backend::kNloptAuglag) {
      nlopt::opt local(nlopt::LD_CCSAQ, n);
      ApplyStopping(
          local, settings.local_xtol_rel >= 0 ? settings.local_xtol_rel : settings.xtol_rel,
          settings.local_ftol_rel >= 0 ? settings.local_ftol_rel : settings.ftol_rel, settings,
          settings.local_maxeval > 0 ? settings.local_maxeval : settings.maxeval);
      opt.set_local_optimizer(local);
    }

    std::vector<double> x(n, 0.0);
    if (x0 != nullptr) {
      for (int j = 0; j < nc; ++j) x[j] = std::isfinite((*x0)(j)) ? std::max((*x0)(j), 0.0) : 0.0;
    } else if (which_ == Backend::kNloptSlsqp && problem.num_equalities() > 0) {
      // SLSQP's cold start: the minimum-norm solution of G x = W, clipped at 0. From x = 0 its
      // first least-squares subproblem failed outright on two stiff cases of the collection, and
      // this start lowered its final residual on 7 of the 34 (none got worse by more than noise).
      // AUGLAG keeps x = 0: from this start it lost the raw-SI case (iteration limit).
      const Eigen::VectorXd start =
          Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(problem.G).solve(problem.W);
      for (int j = 0; j < nc; ++j) x[j] = std::isfinite(start(j)) ? std::max(start(j), 0.0) : 0.0;
    }
    // One optimize() call; returns NLopt's result code and the text of a non-NLopt exception.
    const auto run_pass = [&opt, &program](std::vector<double>* point, std::string* what) {
      double value = 0.0;
      try {
        opt.optimize(*point, value);
      } catch (const nlopt::roundoff_limited&) {
        // Usable point: reported with its code.
      } catch (const nlopt::forced_stop&) {
        *what = "forced stop";
      } catch (const std::exception& e) {
        *what = e.what();
      }
      if (program.error() != nullptr) std::rethrow_exception(program.error());
      return static_cast<int>(opt.last_optimize_result());
    };
    const auto hard_failure = [](int code) {
      return code == nlopt::FAILURE || code == nlopt::INVALID_ARGS ||
             code == nlopt::OUT_OF_MEMORY || code == nlopt::FORCED_STOP;
    };
    const auto finite = [](const std::vector<double>& v) {
      return std::all_of(v.begin(), v.end(), [](double e) { return std::isfinite(e); });
    };

    std::string what;
    const auto start = std::chrono::steady_clock::now();
    result.code = run_pass(&x, &what);
    result.message = ResultName(result.code);
    // Second pass from the first pass's point with the objective re-centred there (see the file
    // comment): same algorithm, same stopping rules, the remaining budget.
    const int budget_left = settings.maxeval - program.evaluations();
    const double time_left =
        settings.maxtime -
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const bool recentre =
        settings.recentre >= 0 ? settings.recentre == 1 : which_ != Backend::kNloptSlsqp;
    if (recentre && !hard_failure(result.code) && result.code != nlopt::MAXEVAL_REACHED &&
        result.code != nlopt::MAXTIME_REACHED && finite(x) && budget_left > 0 && time_left > 0) {
      std::vector<double> refined = x;
      std::string refined_what;
      program.Recentre(refined);
      opt.set_maxeval(budget_left);
      opt.set_maxtime(time_left);
      const int code = run_pass(&refined, &refined_what);
      if (!hard_failure(code) && finite(refined)) {
        result.message = ResultName(result.code) + ", then re-centred pass: " + ResultName(code);
        result.code = code;
        x = refined;
        what = refined_what;
      } else {
        result.message += " (re-centred pass failed: " + ResultName(code) +
                          (refined_what.empty() ? "" : ": " + refined_what) +
                          "; first-pass point kept)";
      }
    }
    if (!what.empty() && what != "nlopt failure") result.message += ": " + what;
    result.iterations = program.evaluations();
    result.limit_reached =
        result.code == nlopt::MAXEVAL_REACHED || result.code == nlopt::MAXTIME_REACHED;
    result.failed = hard_failure(result.code);
    Eigen::VectorXd force(nc);
    for (int j = 0; j < nc; ++j) force(j) = x[j];
    if (force.allFinite()) {
      result.force = force;
    } else {
      result.failed = true;
      result.message += " (no finite point returned)";
    }
    return result;
  }

 private:
  Backend which_;
};

}  // namespace

std::unique_ptr<BackendImpl> MakeNloptBackend(Backend which) {
  if (which != Backend::kNloptSlsqp && which != Backend::kNloptLbfgs &&
      which != Backend::kNloptAuglag) {
    throw std::invalid_argument(
        "MakeNloptBackend: backend = " + std::to_string(static_cast<int>(which)) +
        " is not an NLopt back end (nlopt-slsqp, nlopt-lbfgs, nlopt-auglag)");
  }
  return std::make_unique<NloptBackend>(which);
}

}  // namespace epicycle::solvers::internal
