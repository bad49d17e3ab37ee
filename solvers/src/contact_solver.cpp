// The driver: nondimensionalise, run the back end, recover multipliers, judge by one residual.
#include "epicycle/solvers/contact_solver.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include <Eigen/QR>

#include "backend.hpp"
#include "direct_newton.hpp"
#include "epicycle/io/enum_names.hpp"

namespace epicycle::solvers {
namespace {

using Clock = std::chrono::steady_clock;

std::unique_ptr<internal::BackendImpl> MakeImpl(Backend backend) {
  switch (backend) {
    case Backend::kActiveSetNewton:
      return internal::MakeActiveSetNewtonBackend();
    case Backend::kIpopt:
      return internal::MakeIpoptBackend();
    case Backend::kNloptSlsqp:
    case Backend::kNloptLbfgs:
    case Backend::kNloptAuglag:
      return internal::MakeNloptBackend(backend);
  }
  throw std::invalid_argument("backend = " + std::to_string(static_cast<int>(backend)) +
                              ": not a known back end");
}

// "%.3e", the text std::ostringstream with precision 3 and std::scientific prints (also for inf
// and nan), by std::to_chars: no stream construction or locale look-up, a few times per solve.
std::string Sci(double v) {
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific, 3).ptr;
  return std::string(buf, end);
}

// λ from the active set when the back end does not return it: the least-squares solution of
//   G̃_Aᵀ λ = ∇Φ(x)_A  (g_A = 0 on A = {x_j > 1e-6·max(1, ‖x‖∞)})  and, with supports,
//   S̃ λ = W̃ − G̃x,
// minimum-norm if rank deficient (complete orthogonal decomposition).
Eigen::VectorXd RecoverMultipliers(const internal::ScaledProblem& sp, const Eigen::VectorXd& x) {
  const int m = sp.num_equalities();
  if (m == 0) return Eigen::VectorXd();
  Eigen::VectorXd grad;
  sp.Gradient(x, &grad);
  const double thresh = 1e-6 * std::max(1.0, x.cwiseAbs().maxCoeff());
  std::vector<int> active;
  for (int j = 0; j < sp.num_contacts(); ++j)
    if (x(j) > thresh) active.push_back(j);
  const int na = static_cast<int>(active.size());
  const int rows = na + (sp.has_support ? m : 0);
  Eigen::MatrixXd a(rows, m);
  Eigen::VectorXd b(rows);
  for (int k = 0; k < na; ++k) {
    a.row(k) = sp.G.col(active[k]).transpose();
    b(k) = grad(active[k]);
  }
  if (sp.has_support) {
    a.bottomRows(m) = sp.S;
    b.tail(m) = sp.W - sp.G * x;
  }
  if (rows == 0) return Eigen::VectorXd::Zero(m);
  return Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(a).solve(b);
}

class DriverSolver final : public ContactSolver {
 public:
  DriverSolver(Backend backend, std::unique_ptr<internal::DirectPath> direct)
      : backend_(backend), impl_(MakeImpl(backend)), direct_(std::move(direct)) {}
  Backend backend() const override { return backend_; }
  bool available() const override { return impl_->available(); }

  ContactReport Solve(const ContactProblem& problem, const ContactOptions& options,
                      ContactSolution* in_out) override {
    ContactReport report;
    SolveInto(problem, options, in_out, &report);
    return report;
  }

  void SolveInto(const ContactProblem& problem, const ContactOptions& options,
                 ContactSolution* in_out, ContactReport* out) override {
    const auto t0 = Clock::now();
    if (in_out == nullptr) throw std::invalid_argument("in_out = null: must point to a solution");
    options.Validate();
    const int n = problem.num_contacts();
    const int m = problem.num_equalities();
    if (options.warm_start && (in_out->force.size() != n || in_out->multiplier.size() != m))
      throw std::invalid_argument(
          "warm start solution has " + std::to_string(in_out->force.size()) + " forces and " +
          std::to_string(in_out->multiplier.size()) +
          " multipliers: must have N = " + std::to_string(n) + " and m = " + std::to_string(m));
    if (options.warm_start && (!in_out->force.allFinite() || !in_out->multiplier.allFinite()))
      throw std::invalid_argument("warm start solution: every entry must be finite");

    // A fresh report that keeps the message's storage of the one it replaces.
    std::string kept = std::move(out->message);
    kept.clear();
    *out = ContactReport{};
    out->message = std::move(kept);
    ContactReport& report = *out;
    report.backend = backend_;
    if (!impl_->available()) {
      report.status = ContactStatus::kBackendUnavailable;
      report.message = BackendName(backend_) + " is not compiled into this build";
      in_out->force = Eigen::VectorXd::Zero(n);
      in_out->multiplier = Eigen::VectorXd::Zero(m);
      report.residual.total = report.residual.complementarity = report.residual.equilibrium =
          std::numeric_limits<double>::infinity();
      return;
    }

    // Kept between calls (storage reused); rebuilt from this problem on every call.
    internal::MakeScaledProblem(problem, &sp_);
    const internal::ScaledProblem& sp = sp_;
    Eigen::VectorXd& x0 = x0_;
    Eigen::VectorXd& l0 = l0_;
    if (options.warm_start) internal::Scale(sp, *in_out, &x0, &l0);

    // Positions given (no equalities) and no back-end knobs: the Newton's direct path first. Its
    // iterates are proposals judged by the driver's own residual, computed here from the forces
    // alone (the path has no stopping test of its own); if none meets the tolerance, the general
    // path runs.
    std::string direct_note;
    if (backend_ == Backend::kActiveSetNewton && m == 0 && options.backend_options.empty() &&
        direct_ != nullptr) {
      const auto t1 = Clock::now();
      if (!options.warm_start || x0.size() != n) x0.setZero(n);
      direct_->Begin(options.warm_start);
      // The driver runs the path's iterations and judges every iterate by its own residual (the
      // gap and slopes it computes here are what the path steps from): stop at a tenth of the
      // tolerance at x ≥ 0; give up after three iterates without a new best residual (cycling
      // between active sets, or worse), at the iteration limit, or when the path cannot step.
      const double target = 0.1 * options.tolerance;
      const int max_iterations = std::min(options.max_iterations, 50);
      double best = std::numeric_limits<double>::infinity();
      int since_best = 0, iterations = 0;
      bool accepted = false;
      for (;; ++iterations) {
        bool negative = false;
        const double res = sp.NaturalResidual(x0, internal::kDerivativeFloor, &u_, &du_, &gap_,
                                              &negative);
        if (!std::isfinite(res)) break;
        if (res <= target && !negative) {
          accepted = true;
          report.residual.complementarity = report.residual.total = res;
          break;
        }
        if (res < best) {
          best = res;
          since_best = 0;
        } else if (++since_best >= 3) {
          break;
        }
        if (iterations >= max_iterations ||
            !direct_->Step(sp, gap_, du_, iterations, target, &x0))
          break;
      }
      if (accepted) {
        report.solve_seconds = std::chrono::duration<double>(Clock::now() - t1).count();
        report.iterations = iterations;
        report.status = ContactStatus::kConverged;
        report.active_contacts = static_cast<int>((x0.array() > gap_.array()).count());
        internal::Unscale(sp, x0, Eigen::VectorXd(), in_out);
        std::string& msg = report.message;  // its storage kept: no allocation when reused
        msg.reserve(160);
        msg.append("converged: newton: residual ")
            .append(Sci(report.residual.total))
            .append(" (direct path: no equalities, ")
            .append(std::to_string(iterations))
            .append(" iterations)");
        AppendValidityWarning(sp, x0, &report.message);
        report.total_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
        return;
      }
      direct_note = "; the direct path gave up after " + std::to_string(iterations) +
                    " iterations: its iterates missed the tolerance by the driver's residual (best " +
                    Sci(best) + "), the globalised Newton ran";
      if (options.warm_start) internal::Scale(sp, *in_out, &x0, &l0);
    }

    internal::BackendResult raw;
    std::string exception_text;
    const auto t1 = Clock::now();
    try {
      raw = impl_->Run(sp, options, options.warm_start ? &x0 : nullptr,
                       options.warm_start ? &l0 : nullptr);
    } catch (const std::invalid_argument&) {
      throw;  // misuse (bad back-end option): the caller's error
    } catch (const std::exception& ex) {
      raw = internal::BackendResult();
      raw.failed = true;
      exception_text = ex.what();
    }
    report.solve_seconds = std::chrono::duration<double>(Clock::now() - t1).count();
    report.iterations = raw.iterations;
    report.backend_code = raw.code;

    std::string msg = raw.message.empty() ? exception_text : raw.message;
    if (!exception_text.empty() && !raw.message.empty()) msg += "; " + exception_text;
    bool usable = raw.force.size() == n && raw.force.allFinite();
    bool recovered = false;
    if (usable && (raw.multiplier.size() != m || !raw.multiplier.allFinite())) {
      raw.multiplier = RecoverMultipliers(sp, raw.force.cwiseMax(0.0));
      recovered = m > 0;
    }
    if (usable && !raw.multiplier.allFinite()) usable = false;

    Eigen::VectorXd x, lambda;
    if (usable) {
      x = raw.force;
      lambda = raw.multiplier;
      report.residual = sp.Residuals(x, lambda, &gap_);
      if (!std::isfinite(report.residual.total)) usable = false;
    }
    if (!usable) {
      const bool had_nan = raw.force.size() == n && !raw.force.allFinite();
      report.status = ContactStatus::kNumericalFailure;
      report.message = "back end returned no usable point" +
                       std::string(had_nan ? " (NaN/Inf in its answer; solution set to zeros)"
                                           : " (solution set to zeros)") +
                       (msg.empty() ? "" : ": " + msg);
      in_out->force = Eigen::VectorXd::Zero(n);
      in_out->multiplier = Eigen::VectorXd::Zero(m);
      report.residual = sp.Residuals(Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(m));
      report.total_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      return;
    }

    report.status = Judge(report.residual.total, options.tolerance, raw);
    std::string text = BackendName(backend_) + ": residual " + Sci(report.residual.total) +
                       " (complementarity " + Sci(report.residual.complementarity) +
                       ", equilibrium " + Sci(report.residual.equilibrium) + ")";
    if (recovered) text += "; multipliers recovered by least squares on the active set";
    text += direct_note;
    if (!msg.empty()) text += "; back end says: " + msg;

    if (options.polish && report.status != ContactStatus::kConverged) {
      // Separate, labelled step: active-set Newton warm-started from the raw answer.
      auto newton = internal::MakeActiveSetNewtonBackend();
      ContactOptions po = options;
      po.backend_options.clear();
      Eigen::VectorXd xc = x.cwiseMax(0.0);
      internal::BackendResult pol = newton->Run(sp, po, &xc, &lambda);
      if (pol.force.size() == n && pol.force.allFinite() && pol.multiplier.allFinite()) {
        Eigen::VectorXd pol_gap;
        const ContactResiduals pr = sp.Residuals(pol.force, pol.multiplier, &pol_gap);
        if (pr.total < report.residual.total) {
          text += "; POLISHED by active-set Newton: residual " + Sci(report.residual.total) +
                  " -> " + Sci(pr.total);
          x = pol.force;
          lambda = pol.multiplier;
          report.residual = pr;
          gap_.swap(pol_gap);
          report.polished = true;
          raw.failed = pol.failed;
          raw.limit_reached = pol.limit_reached;
          report.status = Judge(pr.total, options.tolerance, raw);
        }
      }
    }

    if (report.status != ContactStatus::kConverged && m > 0 && !sp.has_support &&
        internal::EqualitiesInfeasible(sp)) {
      report.status = ContactStatus::kInfeasible;
      text += "; no F >= 0 satisfies G F = W (non-negative least squares residual > 0)";
    }

    internal::Unscale(sp, x.cwiseMax(0.0), lambda, in_out);
    // Active in the sense of the natural map (x_j > g_j): a force an interior-point method
    // leaves at 1e-12 instead of 0 does not count. g is the gap of the residual just computed
    // at the same (max(x, 0), λ).
    report.active_contacts = static_cast<int>((x.array().max(0.0) > gap_.array()).count());
    report.message = StatusName(report.status) + ": " + text;
    AppendValidityWarning(sp, x.cwiseMax(0.0), &report.message);
    report.total_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  }

 private:
  static ContactStatus Judge(double residual, double tol, const internal::BackendResult& raw) {
    if (residual <= tol) return ContactStatus::kConverged;
    if (residual <= 100.0 * tol && !raw.failed) return ContactStatus::kConvergedInaccurate;
    if (raw.limit_reached) return ContactStatus::kIterationLimit;
    return ContactStatus::kNumericalFailure;
  }

  // Contacts loaded beyond the local term's validity (Hertz half-width L > depth h) are named in
  // the message as a warning. In scaled units L² = l2·x, so the limit is x = min_B h_B²/l2, the
  // force ValidityLimitForce() gives for the unscaled problem (to round-off).
  static void AppendValidityWarning(const internal::ScaledProblem& sp, const Eigen::VectorXd& x,
                                    std::string* message) {
    if (!sp.has_local) return;
    int beyond = 0;
    for (int j = 0; j < sp.num_contacts(); ++j) {
      const internal::ScaledProblem::Local& l = sp.local[j];
      const double h = std::min(l.h[0], l.h[1]);
      if (l.enabled && x(j) > 0.0 && x(j) * l.l2 > h * h) ++beyond;
    }
    if (beyond > 0)
      *message += "; WARNING: " + std::to_string(beyond) +
                  " contact(s) beyond the local term's validity (Hertz half-width L > depth h)";
  }

  Backend backend_;
  std::unique_ptr<internal::BackendImpl> impl_;
  std::unique_ptr<internal::DirectPath> direct_;  // null: no direct path
  // Work storage reused from call to call (the solver is stateful and not shared between
  // threads): the scaled problem, the scaled warm start, the gap of the final residual.
  internal::ScaledProblem sp_;
  Eigen::VectorXd x0_, l0_, gap_;
  Eigen::VectorXd u_, du_;  // the direct path's iterate: local terms and their slopes
};

}  // namespace

namespace {

// The back ends' names, in the order of AllBackends(): the one table of BackendName and
// BackendFromName.
constexpr std::array<io::EnumName<Backend>, 5> kBackendNames{{
    {Backend::kActiveSetNewton, "newton"},
    {Backend::kIpopt, "ipopt"},
    {Backend::kNloptSlsqp, "nlopt-slsqp"},
    {Backend::kNloptLbfgs, "nlopt-lbfgs"},
    {Backend::kNloptAuglag, "nlopt-auglag"},
}};

constexpr std::array<io::EnumName<ContactStatus>, 6> kStatusNames{{
    {ContactStatus::kConverged, "converged"},
    {ContactStatus::kConvergedInaccurate, "converged-inaccurate"},
    {ContactStatus::kIterationLimit, "iteration-limit"},
    {ContactStatus::kNumericalFailure, "numerical-failure"},
    {ContactStatus::kInfeasible, "infeasible"},
    {ContactStatus::kBackendUnavailable, "backend-unavailable"},
}};

}  // namespace

std::string BackendName(Backend backend) {
  if (const char* name = io::NameOf(kBackendNames, backend)) return name;
  return "unknown(" + std::to_string(static_cast<int>(backend)) + ")";
}

Backend BackendFromName(const std::string& name) {
  if (const std::optional<Backend> b = io::ValueOf(kBackendNames, name)) return *b;
  throw std::invalid_argument("backend = '" + name + "': must be one of " +
                              io::NameList(kBackendNames));
}

std::string StatusName(ContactStatus status) {
  if (const char* name = io::NameOf(kStatusNames, status)) return name;
  return "unknown";
}

void ContactOptions::Validate() const {
  auto fail = [](const std::string& field, const std::string& value, const std::string& rule) {
    throw std::invalid_argument("ContactOptions." + field + " = " + value + ": " + rule);
  };
  if (!std::isfinite(tolerance) || !(tolerance > 0.0))
    fail("tolerance", Sci(tolerance), "must be finite and > 0");
  if (max_iterations < 1) fail("max_iterations", std::to_string(max_iterations), "must be >= 1");
  if (!(time_limit > 0.0)) fail("time_limit", Sci(time_limit), "must be > 0");
  if (backend_options.empty()) return;
  // The keys are fixed at compile time: collected once, not by building every back end per call.
  static const std::map<std::string, std::set<std::string>> known = [] {
    std::map<std::string, std::set<std::string>> keys;
    for (Backend b : AllBackends()) {
      const std::string ns = b == Backend::kActiveSetNewton ? "newton"
                             : b == Backend::kIpopt         ? "ipopt"
                                                            : "nlopt";
      for (const std::string& k : MakeImpl(b)->option_keys()) keys[ns].insert(k);
    }
    return keys;
  }();
  for (const auto& [key, value] : backend_options) {
    const auto dot = key.find('.');
    const std::string ns = dot == std::string::npos ? "" : key.substr(0, dot);
    const std::string rest = dot == std::string::npos ? key : key.substr(dot + 1);
    const auto it = known.find(ns);
    if (it == known.end() || !it->second.count(rest)) {
      std::string list;
      for (const auto& [n2, keys] : known)
        for (const auto& k : keys) list += (list.empty() ? "" : ", ") + n2 + "." + k;
      fail("backend_options[" + key + "]", "'" + value + "'",
           "unknown key; known keys: " + (list.empty() ? std::string("none") : list));
    }
  }
}

std::unique_ptr<ContactSolver> MakeContactSolver(Backend backend) {
  return std::make_unique<DriverSolver>(backend, std::make_unique<internal::DirectNewton>());
}

std::unique_ptr<ContactSolver> internal::MakeDriverSolver(Backend backend,
                                                          std::unique_ptr<DirectPath> direct) {
  return std::make_unique<DriverSolver>(backend, std::move(direct));
}

ContactScales ComputeContactScales(const ContactProblem& problem) {
  const internal::ScaledProblem sp = internal::MakeScaledProblem(problem);
  return {sp.force_scale, sp.length_scale, sp.row_scale};
}

SolutionDifference CompareSolutions(const ContactProblem& problem, const ContactSolution& a,
                                    const ContactSolution& ref) {
  const ContactScales sc = ComputeContactScales(problem);
  const int n = problem.num_contacts(), m = problem.num_equalities();
  if (a.force.size() != n || ref.force.size() != n || a.multiplier.size() != m ||
      ref.multiplier.size() != m)
    throw std::invalid_argument(
        "CompareSolutions: solution sizes must be N = " + std::to_string(n) +
        " forces and m = " + std::to_string(m) + " multipliers");
  SolutionDifference d;
  d.force = (a.force - ref.force).cwiseAbs().maxCoeff() /
            std::max(ref.force.cwiseAbs().maxCoeff(), sc.force);
  if (m > 0) {
    const Eigen::VectorXd da = (a.multiplier - ref.multiplier).cwiseProduct(sc.row);
    d.multiplier = da.cwiseAbs().maxCoeff() /
                   std::max(ref.multiplier.cwiseProduct(sc.row).cwiseAbs().maxCoeff(), sc.length);
    const Eigen::MatrixXd& g = problem.equality_matrix();
    d.displacement = (g.transpose() * (a.multiplier - ref.multiplier)).cwiseAbs().maxCoeff() /
                     std::max((g.transpose() * ref.multiplier).cwiseAbs().maxCoeff(), sc.length);
  }
  if (!std::isfinite(d.force)) d.force = std::numeric_limits<double>::infinity();
  if (!std::isfinite(d.multiplier)) d.multiplier = std::numeric_limits<double>::infinity();
  if (!std::isfinite(d.displacement)) d.displacement = std::numeric_limits<double>::infinity();
  return d;
}

ContactResiduals EvaluateResiduals(const ContactProblem& problem, const ContactSolution& solution) {
  const int n = problem.num_contacts(), m = problem.num_equalities();
  if (solution.force.size() != n || solution.multiplier.size() != m)
    throw std::invalid_argument("EvaluateResiduals: a solution of N = " + std::to_string(n) +
                                " forces and m = " + std::to_string(m) + " multipliers, not " +
                                std::to_string(solution.force.size()) + " and " +
                                std::to_string(solution.multiplier.size()));
  const internal::ScaledProblem sp = internal::MakeScaledProblem(problem);
  Eigen::VectorXd x, lambda;
  internal::Scale(sp, solution, &x, &lambda);
  return sp.Residuals(x, lambda);
}

std::vector<Backend> AllBackends() {
  std::vector<Backend> all;
  for (const auto& e : kBackendNames) all.push_back(e.value);
  return all;
}

std::vector<Backend> AvailableBackends() {
  std::vector<Backend> out;
  for (Backend b : AllBackends())
    if (MakeImpl(b)->available()) out.push_back(b);
  return out;
}

}  // namespace epicycle::solvers
