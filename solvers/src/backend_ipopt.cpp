// Ipopt back end: the contact problem as an Ipopt TNLP with the exact Hessian.
//
// Variables. x = F (scaled forces), bounds x ≥ 0. When the support compliance S has non-zero
// entries, extra free variables y are added for the supported rows P = {i : S(i,:) ≠ 0} (S is
// symmetric PSD, so a zero row is also a zero column):
//
//   min  Φ(x) + ½ y_Pᵀ S_PP y_P     s.t.  x ≥ 0,   G x + S(:,P) y_P = W.
//
// Stationarity in y gives S_PP (y_P − λ_P) = 0, so λ = y on range(S); the multipliers of the
// equality rows are λ themselves and are what this back end returns. Rows outside P are hard
// equalities. The program is convex while the local terms are increasing (docs/model.md §5).
//
// Sign convention. Ipopt's Lagrangian is f + cᵀλ_ipopt − z_Lᵀ(x − x_L); the problem's stationarity
// is ∇Φ − Gᵀλ − μ = 0, so λ = −λ_ipopt.
//
// Bound relaxation. Ipopt by default relaxes every bound by bound_relax_factor = 1e-8 (absolute for
// a zero bound), so forces that should be zero come back as ≈ −1e-9…+1e-8 and are judged by the
// driver's natural-map residual as that much off. We set bound_relax_factor = 0: the interior-point
// iterates then stay strictly positive and an open contact ends at F ≈ μ_final / g, far below any
// tolerance we accept. The user can override it ("ipopt.bound_relax_factor").
//
// Tolerances. Ipopt gets tol = constr_viol_tol = dual_inf_tol = kToleranceFactor·tolerance and
// compl_inf_tol = kComplementarityFactor·tolerance (see those constants for why); the
// "acceptable" set is 100× that (the driver's kConvergedInaccurate band); mu_min is a tenth of
// compl_inf_tol when that is below Ipopt's default (1e-11), otherwise Ipopt could not drive x·z
// that low. The default mu_strategy stays "monotone": "adaptive" saves iterations but on the
// stage-sized problems stalls a factor 4 above a 1e-10 residual. The driver still judges the
// answer by its own residual.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wconversion"
#include <coin/IpIpoptApplication.hpp>
#include <coin/IpRegOptions.hpp>
#include <coin/IpSolveStatistics.hpp>
#include <coin/IpTNLP.hpp>
#pragma GCC diagnostic pop

#include "backend.hpp"

namespace epicycle::solvers::internal {
namespace {

using Ipopt::Index;
using Ipopt::Number;

constexpr char kNamespace[] = "ipopt.";

// Ipopt measures complementarity as x_j·z_j ≈ μ, the driver as min(x_j, g_j): an open contact
// with a small gap g_j ends at x_j ≈ μ/g_j, a factor 1/g_j above Ipopt's measure. On the
// stage-sized problems (bench_contact) that factor is 4 to 64; with compl_inf_tol a thousandth of
// the driver's tolerance they converge at every tolerance from 1e-6 to 1e-12 for at most one
// extra iteration (a tenth left the 56-contact problem 6× above tolerance). Ipopt's overall,
// feasibility and dual tolerances are set to a tenth.
constexpr double kToleranceFactor = 0.1;
constexpr double kComplementarityFactor = 1e-3;

enum class OptionType { kString, kInteger, kNumber };

struct KnownOption {
  const char* key;
  OptionType type;
};

// The Ipopt options a user may pass as "ipopt.<key>". Kept to the ones that make sense for this
// problem class; anything else is rejected so that a typo does not go unnoticed.
constexpr KnownOption kKnownOptions[] = {
    {"tol", OptionType::kNumber},
    {"acceptable_tol", OptionType::kNumber},
    {"acceptable_iter", OptionType::kInteger},
    {"constr_viol_tol", OptionType::kNumber},
    {"dual_inf_tol", OptionType::kNumber},
    {"compl_inf_tol", OptionType::kNumber},
    {"max_iter", OptionType::kInteger},
    {"max_cpu_time", OptionType::kNumber},
    {"print_level", OptionType::kInteger},
    {"mu_strategy", OptionType::kString},
    {"mu_oracle", OptionType::kString},
    {"mu_init", OptionType::kNumber},
    {"mu_min", OptionType::kNumber},
    {"mu_target", OptionType::kNumber},
    {"bound_relax_factor", OptionType::kNumber},
    {"honor_original_bounds", OptionType::kString},
    {"bound_push", OptionType::kNumber},
    {"bound_frac", OptionType::kNumber},
    {"bound_mult_init_val", OptionType::kNumber},
    {"linear_solver", OptionType::kString},
    {"linear_system_scaling", OptionType::kString},
    {"nlp_scaling_method", OptionType::kString},
    {"hessian_approximation", OptionType::kString},
    {"warm_start_init_point", OptionType::kString},
    {"warm_start_bound_push", OptionType::kNumber},
    {"warm_start_mult_bound_push", OptionType::kNumber},
    {"mehrotra_algorithm", OptionType::kString},
    {"fixed_variable_treatment", OptionType::kString},
    {"expect_infeasible_problem", OptionType::kString},
    {"derivative_test", OptionType::kString},
};

const KnownOption* FindOption(const std::string& key) {
  for (const KnownOption& option : kKnownOptions) {
    if (key == option.key) return &option;
  }
  return nullptr;
}

[[noreturn]] void ThrowBadOption(const std::string& full_key, const std::string& value,
                                 const std::string& rule) {
  std::ostringstream os;
  os << "ContactOptions.backend_options[\"" << full_key << "\"] = \"" << value << "\": " << rule;
  throw std::invalid_argument(os.str());
}

double ParseNumber(const std::string& full_key, const std::string& value) {
  const char* begin = value.c_str();
  char* end = nullptr;
  const double parsed = std::strtod(begin, &end);
  if (value.empty() || end != begin + value.size() || !std::isfinite(parsed)) {
    ThrowBadOption(full_key, value, "must be a finite number");
  }
  return parsed;
}

Index ParseInteger(const std::string& full_key, const std::string& value) {
  const char* begin = value.c_str();
  char* end = nullptr;
  const long parsed = std::strtol(begin, &end, 10);
  if (value.empty() || end != begin + value.size() || parsed < std::numeric_limits<Index>::min() ||
      parsed > std::numeric_limits<Index>::max()) {
    ThrowBadOption(full_key, value, "must be an integer");
  }
  return static_cast<Index>(parsed);
}

std::string StatusName(Ipopt::ApplicationReturnStatus status) {
  switch (status) {
    case Ipopt::Solve_Succeeded:
      return "Solve_Succeeded";
    case Ipopt::Solved_To_Acceptable_Level:
      return "Solved_To_Acceptable_Level";
    case Ipopt::Infeasible_Problem_Detected:
      return "Infeasible_Problem_Detected";
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return "Search_Direction_Becomes_Too_Small";
    case Ipopt::Diverging_Iterates:
      return "Diverging_Iterates";
    case Ipopt::User_Requested_Stop:
      return "User_Requested_Stop";
    case Ipopt::Feasible_Point_Found:
      return "Feasible_Point_Found";
    case Ipopt::Maximum_Iterations_Exceeded:
      return "Maximum_Iterations_Exceeded";
    case Ipopt::Restoration_Failed:
      return "Restoration_Failed";
    case Ipopt::Error_In_Step_Computation:
      return "Error_In_Step_Computation";
    case Ipopt::Maximum_CpuTime_Exceeded:
      return "Maximum_CpuTime_Exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return "Not_Enough_Degrees_Of_Freedom";
    case Ipopt::Invalid_Problem_Definition:
      return "Invalid_Problem_Definition";
    case Ipopt::Invalid_Option:
      return "Invalid_Option";
    case Ipopt::Invalid_Number_Detected:
      return "Invalid_Number_Detected";
    case Ipopt::Unrecoverable_Exception:
      return "Unrecoverable_Exception";
    case Ipopt::NonIpopt_Exception_Thrown:
      return "NonIpopt_Exception_Thrown";
    case Ipopt::Insufficient_Memory:
      return "Insufficient_Memory";
    case Ipopt::Internal_Error:
      return "Internal_Error";
  }
  return "Ipopt status " + std::to_string(static_cast<int>(status));
}

// The TNLP. Holds references to the problem; lives only for one Run().
class ContactTnlp final : public Ipopt::TNLP {
 public:
  ContactTnlp(const ScaledProblem& problem, const Eigen::VectorXd* x0,
              const Eigen::VectorXd* lambda0, bool warm_start_multipliers)
      : problem_(problem),
        x0_(x0),
        lambda0_(lambda0),
        warm_start_multipliers_(warm_start_multipliers),
        num_contacts_(problem.num_contacts()),
        num_equalities_(problem.num_equalities()) {
    if (problem.has_support) {
      for (int i = 0; i < num_equalities_; ++i) {
        if (problem.S.row(i).cwiseAbs().maxCoeff() > 0.0) supported_.push_back(i);
      }
    }
    num_support_ = static_cast<int>(supported_.size());
    // Structural non-zeros of the constraint Jacobian [G | S(:,P)].
    for (int i = 0; i < num_equalities_; ++i) {
      for (int j = 0; j < num_contacts_; ++j) {
        if (problem.G(i, j) != 0.0) jacobian_.push_back({i, j, problem.G(i, j)});
      }
      for (int k = 0; k < num_support_; ++k) {
        const double s = problem.S(i, supported_[k]);
        if (s != 0.0) jacobian_.push_back({i, num_contacts_ + k, s});
      }
    }
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = num_contacts_ + num_support_;
    m = num_equalities_;
    nnz_jac_g = static_cast<Index>(jacobian_.size());
    nnz_h_lag = num_contacts_ * (num_contacts_ + 1) / 2 + num_support_ * (num_support_ + 1) / 2;
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l,
                       Number* g_u) override {
    constexpr double kInf = 2e19;  // Ipopt's default nlp_upper_bound_inf is 1e19
    for (Index i = 0; i < n; ++i) {
      x_l[i] = i < num_contacts_ ? 0.0 : -kInf;
      x_u[i] = kInf;
    }
    for (Index i = 0; i < m; ++i) g_l[i] = g_u[i] = problem_.W(i);
    return true;
  }

  bool get_constraints_linearity(Index m, LinearityType* const_types) override {
    for (Index i = 0; i < m; ++i) const_types[i] = LINEAR;
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number* z_l, Number* z_u,
                          Index m, bool init_lambda, Number* lambda) override {
    return Guard([&] {
      if (init_x) {
        for (Index i = 0; i < n; ++i) x[i] = 0.0;
        if (x0_ != nullptr) {
          for (int j = 0; j < num_contacts_; ++j) x[j] = std::max((*x0_)(j), 0.0);
        }
        if (lambda0_ != nullptr) {
          for (int k = 0; k < num_support_; ++k) x[num_contacts_ + k] = (*lambda0_)(supported_[k]);
        }
      }
      // Multipliers only when Ipopt asks for them (warm_start_init_point = yes).
      if (init_z || init_lambda) {
        if (!warm_start_multipliers_ || x0_ == nullptr || lambda0_ == nullptr) return false;
        Eigen::VectorXd xv = x0_->cwiseMax(0.0);
        Eigen::VectorXd gradient;
        problem_.Gradient(xv, &gradient);
        const Eigen::VectorXd gap = gradient - problem_.G.transpose() * (*lambda0_);
        for (Index i = 0; i < n; ++i) {
          // The bound multiplier of x_j is the gap g_j; y is free (no bound multipliers).
          if (init_z) {
            z_l[i] = i < num_contacts_ ? std::max(gap(i), 0.0) : 0.0;
            z_u[i] = 0.0;
          }
        }
        if (init_lambda) {
          for (Index i = 0; i < m; ++i) lambda[i] = -(*lambda0_)(i);
        }
      }
      return true;
    });
  }

  bool eval_f(Index n, const Number* x, bool, Number& obj_value) override {
    return Guard([&] {
      if (!Load(n, x)) return false;
      double value = problem_.Objective(x_);
      if (num_support_ > 0) value += 0.5 * y_.dot(SupportBlock() * y_);
      obj_value = value;
      return std::isfinite(value);
    });
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* grad_f) override {
    return Guard([&] {
      if (!Load(n, x)) return false;
      problem_.Gradient(x_, &gradient_);
      for (int j = 0; j < num_contacts_; ++j) grad_f[j] = gradient_(j);
      if (num_support_ > 0) {
        const Eigen::VectorXd sy = SupportBlock() * y_;
        for (int k = 0; k < num_support_; ++k) grad_f[num_contacts_ + k] = sy(k);
      }
      for (Index i = 0; i < n; ++i) {
        if (!std::isfinite(grad_f[i])) return false;
      }
      return true;
    });
  }

  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    return Guard([&] {
      for (Index i = 0; i < m; ++i) g[i] = 0.0;
      for (const Entry& e : jacobian_) g[e.row] += e.value * x[e.col];
      for (Index i = 0; i < m; ++i) {
        if (!std::isfinite(g[i])) return false;
      }
      (void)n;
      return true;
    });
  }

  bool eval_jac_g(Index, const Number*, bool, Index, Index nele_jac, Index* i_row, Index* j_col,
                  Number* values) override {
    return Guard([&] {
      if (nele_jac != static_cast<Index>(jacobian_.size())) return false;
      for (Index k = 0; k < nele_jac; ++k) {
        if (values == nullptr) {
          i_row[k] = jacobian_[k].row;
          j_col[k] = jacobian_[k].col;
        } else {
          values[k] = jacobian_[k].value;
        }
      }
      return true;
    });
  }

  bool eval_h(Index n, const Number* x, bool, Number obj_factor, Index, const Number*, bool,
              Index nele_hess, Index* i_row, Index* j_col, Number* values) override {
    return Guard([&] {
      Index k = 0;
      if (values == nullptr) {
        for (int i = 0; i < num_contacts_; ++i) {
          for (int j = 0; j <= i; ++j, ++k) {
            i_row[k] = i;
            j_col[k] = j;
          }
        }
        for (int a = 0; a < num_support_; ++a) {
          for (int b = 0; b <= a; ++b, ++k) {
            i_row[k] = num_contacts_ + a;
            j_col[k] = num_contacts_ + b;
          }
        }
        return k == nele_hess;
      }
      if (!Load(n, x)) return false;
      // ∇²Φ = C + diag(u'(x)). u' grows like ln(1/x) as x → 0⁺: interior iterates keep x > 0,
      // but evaluate at no less than the smallest normal double so that a zero never yields +∞.
      derivative_.setZero(num_contacts_);
      if (problem_.has_local) {
        const Eigen::VectorXd guarded = x_.cwiseMax(std::numeric_limits<double>::min());
        problem_.LocalDerivative(guarded, &derivative_);
        if (!derivative_.allFinite()) return false;
      }
      for (int i = 0; i < num_contacts_; ++i) {
        for (int j = 0; j <= i; ++j, ++k) {
          double h = problem_.C(i, j);
          if (i == j) h += derivative_(i);
          values[k] = obj_factor * h;
        }
      }
      for (int a = 0; a < num_support_; ++a) {
        for (int b = 0; b <= a; ++b, ++k) {
          values[k] = obj_factor * problem_.S(supported_[a], supported_[b]);
        }
      }
      return k == nele_hess;
    });
  }

  void finalize_solution(Ipopt::SolverReturn status, Index, const Number* x, const Number*,
                         const Number*, Index m, const Number*, const Number* lambda, Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    final_status_ = static_cast<int>(status);
    have_point_ = true;
    force_.resize(num_contacts_);
    for (int j = 0; j < num_contacts_; ++j) force_(j) = x[j];
    multiplier_.resize(m);
    for (Index i = 0; i < m; ++i) multiplier_(i) = -lambda[i];  // see the sign convention above
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Index iter, Number, Number, Number, Number,
                             Number, Number, Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    iterations_ = iter;
    return error_ == nullptr;  // stop Ipopt once a callback has thrown
  }

  bool have_point() const { return have_point_; }
  const Eigen::VectorXd& force() const { return force_; }
  const Eigen::VectorXd& multiplier() const { return multiplier_; }
  int iterations() const { return iterations_; }
  const std::exception_ptr& error() const { return error_; }

 private:
  struct Entry {
    Index row;
    Index col;
    double value;
  };

  // Runs a callback body; an exception is stored (rethrown by Run after Ipopt returns) and the
  // callback reports failure to Ipopt.
  template <typename Body>
  bool Guard(Body&& body) {
    if (error_ != nullptr) return false;
    try {
      return body();
    } catch (...) {
      error_ = std::current_exception();
      return false;
    }
  }

  // Copies Ipopt's x into x_ (forces) and y_ (support variables); false for a point outside the
  // domain (negative or non-finite force), which Ipopt treats as an evaluation error.
  bool Load(Index n, const Number* x) {
    x_.resize(num_contacts_);
    y_.resize(num_support_);
    for (Index i = 0; i < n; ++i) {
      if (!std::isfinite(x[i])) return false;
      if (i < num_contacts_) {
        if (x[i] < 0.0) return false;
        x_(i) = x[i];
      } else {
        y_(i - num_contacts_) = x[i];
      }
    }
    return true;
  }

  Eigen::MatrixXd SupportBlock() const {
    Eigen::MatrixXd block(num_support_, num_support_);
    for (int a = 0; a < num_support_; ++a) {
      for (int b = 0; b < num_support_; ++b) block(a, b) = problem_.S(supported_[a], supported_[b]);
    }
    return block;
  }

  const ScaledProblem& problem_;
  const Eigen::VectorXd* x0_;
  const Eigen::VectorXd* lambda0_;
  bool warm_start_multipliers_;
  int num_contacts_;
  int num_equalities_;
  int num_support_ = 0;
  std::vector<int> supported_;
  std::vector<Entry> jacobian_;

  Eigen::VectorXd x_, y_, gradient_, derivative_;
  Eigen::VectorXd force_, multiplier_;
  bool have_point_ = false;
  int final_status_ = -1;
  int iterations_ = 0;
  std::exception_ptr error_;
};

class IpoptBackend final : public BackendImpl {
 public:
  bool available() const override { return true; }

  std::vector<std::string> option_keys() const override {
    std::vector<std::string> keys;
    for (const KnownOption& option : kKnownOptions) keys.emplace_back(option.key);
    return keys;
  }

  BackendResult Run(const ScaledProblem& problem, const ContactOptions& options,
                    const Eigen::VectorXd* x0, const Eigen::VectorXd* lambda0) override {
    const int n = problem.num_contacts();
    const int m = problem.num_equalities();
    if (x0 != nullptr && x0->size() != n) {
      throw std::invalid_argument("Ipopt back end: warm start x0 has size " +
                                  std::to_string(x0->size()) + ", must equal the " +
                                  std::to_string(n) + " contacts");
    }
    if (lambda0 != nullptr && lambda0->size() != m) {
      throw std::invalid_argument("Ipopt back end: warm start lambda0 has size " +
                                  std::to_string(lambda0->size()) + ", must equal the " +
                                  std::to_string(m) + " equalities");
    }

    // Ipopt 3.11 (Debian 12) calls MUMPS, which is not thread-safe (global Fortran state; Ipopt
    // guards it only from 3.14 on): back-end objects on different threads (a parallel sweep, a
    // study's workers) take turns for the whole solve.
    static std::mutex mumps;
    const std::lock_guard<std::mutex> turn(mumps);
    // One IpoptApplication per back-end object, reused by every Run (creating one registers all of
    // Ipopt's options and dominated the cost of small solves); its options are reset each time.
    if (Ipopt::IsNull(app_)) app_ = IpoptApplicationFactory();
    Ipopt::IpoptApplication* app = Ipopt::GetRawPtr(app_);
    Ipopt::OptionsList& list = *app->Options();
    list.clear();
    const double tol = kToleranceFactor * options.tolerance;
    const double compl_tol = kComplementarityFactor * options.tolerance;
    list.SetStringValue("sb", "yes");  // no banner
    list.SetIntegerValue("print_level", 0);
    list.SetNumericValue("tol", tol);
    list.SetNumericValue("constr_viol_tol", tol);
    list.SetNumericValue("dual_inf_tol", tol);
    list.SetNumericValue("compl_inf_tol", compl_tol);
    list.SetNumericValue("acceptable_tol", 100.0 * tol);
    list.SetNumericValue("acceptable_constr_viol_tol", 100.0 * tol);
    list.SetNumericValue("acceptable_dual_inf_tol", 100.0 * tol);
    list.SetNumericValue("acceptable_compl_inf_tol", 100.0 * compl_tol);
    list.SetNumericValue("mu_min", std::min(1e-11, 0.1 * compl_tol));  // Ipopt default 1e-11
    list.SetIntegerValue("max_iter", options.max_iterations);
    list.SetNumericValue("max_cpu_time", options.time_limit);
    list.SetNumericValue("bound_relax_factor", 0.0);
    list.SetStringValue("honor_original_bounds", "yes");
    list.SetStringValue("jac_c_constant", "yes");
    if (!problem.has_local) list.SetStringValue("hessian_constant", "yes");

    bool warm_start_multipliers = false;
    for (const auto& [full_key, value] : options.backend_options) {
      if (full_key.rfind(kNamespace, 0) != 0) continue;  // another back end's option
      const std::string key = full_key.substr(sizeof(kNamespace) - 1);
      const KnownOption* known = FindOption(key);
      if (known == nullptr) {
        std::string rule = "unknown Ipopt option; known:";
        for (const KnownOption& option : kKnownOptions) rule += std::string(" ") + option.key;
        ThrowBadOption(full_key, value, rule);
      }
      // Check the value against Ipopt's registered range first (silently: a rejected
      // SetXValue prints to the console).
      const Ipopt::SmartPtr<const Ipopt::RegisteredOption> registered =
          app->RegOptions()->GetOption(key);
      bool accepted = Ipopt::IsValid(registered);
      switch (known->type) {
        case OptionType::kString:
          accepted = accepted && registered->IsValidStringSetting(value) &&
                     list.SetStringValue(key, value);
          break;
        case OptionType::kInteger: {
          const Index parsed = ParseInteger(full_key, value);
          accepted = accepted && registered->IsValidIntegerSetting(parsed) &&
                     list.SetIntegerValue(key, parsed);
          break;
        }
        case OptionType::kNumber: {
          const Number parsed = ParseNumber(full_key, value);
          accepted = accepted && registered->IsValidNumberSetting(parsed) &&
                     list.SetNumericValue(key, parsed);
          break;
        }
      }
      if (!accepted) ThrowBadOption(full_key, value, "rejected by Ipopt (not a valid setting)");
      if (key == "warm_start_init_point") warm_start_multipliers = (value == "yes");
    }

    BackendResult result;
    result.force = Eigen::VectorXd::Zero(n);
    if (warm_start_multipliers && (x0 == nullptr || lambda0 == nullptr)) {
      // Nothing to warm-start the multipliers from (no warm start given): Ipopt's own start.
      list.SetStringValue("warm_start_init_point", "no");
      warm_start_multipliers = false;
    }
    if (!initialised_) {
      // Sets up the console journal from print_level (0); later runs keep it.
      const Ipopt::ApplicationReturnStatus init = app->Initialize("");  // no ipopt.opt file
      if (init != Ipopt::Solve_Succeeded) {
        result.failed = true;
        result.code = static_cast<int>(init);
        result.message = "Ipopt initialisation failed: " + StatusName(init);
        return result;
      }
      initialised_ = true;
    }

    Ipopt::SmartPtr<ContactTnlp> tnlp =
        new ContactTnlp(problem, x0, lambda0, warm_start_multipliers);
    const Ipopt::ApplicationReturnStatus status =
        app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(tnlp)));
    if (tnlp->error() != nullptr) std::rethrow_exception(tnlp->error());

    result.code = static_cast<int>(status);
    result.message = StatusName(status);
    result.iterations = tnlp->iterations();
    if (Ipopt::IsValid(app->Statistics())) result.iterations = app->Statistics()->IterationCount();
    result.limit_reached =
        status == Ipopt::Maximum_Iterations_Exceeded || status == Ipopt::Maximum_CpuTime_Exceeded;
    const bool hard_error =
        status == Ipopt::Not_Enough_Degrees_Of_Freedom ||
        status == Ipopt::Invalid_Problem_Definition || status == Ipopt::Invalid_Option ||
        status == Ipopt::Invalid_Number_Detected || status == Ipopt::Unrecoverable_Exception ||
        status == Ipopt::NonIpopt_Exception_Thrown || status == Ipopt::Insufficient_Memory ||
        status == Ipopt::Internal_Error;
    if (tnlp->have_point() && tnlp->force().allFinite() && tnlp->multiplier().allFinite()) {
      result.force = tnlp->force();
      result.multiplier = tnlp->multiplier();
      result.failed = hard_error;
    } else {
      result.failed = true;
      result.message += " (no finite point returned)";
    }
    return result;
  }

 private:
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app_;
  bool initialised_ = false;
};

}  // namespace

std::unique_ptr<BackendImpl> MakeIpoptBackend() { return std::make_unique<IpoptBackend>(); }

}  // namespace epicycle::solvers::internal
