// The contact core of solvers/ from numpy: a contact problem (C, δ0, G, W, K, local terms), solved
// by any back end, with the report (docs/solvers.md).
#include <optional>

#include <pybind11/eigen.h>

#include "common.hpp"
#include "epicycle/report/record_json.hpp"
#include "epicycle/solvers/backend_comparison.hpp"
#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/transmission/record.hpp"
#include "epicycle/transmission/run_arguments.hpp"

namespace epicycle::python {

namespace {

using Problem = solvers::ContactProblem;
using ProblemPtr = std::shared_ptr<Problem>;

solvers::LocalTermParameters LocalTermOf(const py::dict& d) {
  solvers::LocalTermParameters p;
  for (const auto& [key, value] : d) {
    const std::string k = key.cast<std::string>();
    if (k == "enabled") {
      p.enabled = value.cast<bool>();
    } else if (k == "face_width_m") {
      p.face_width = value.cast<double>();
    } else if (k == "reduced_radius_m") {
      p.reduced_radius = value.cast<double>();
    } else if (k == "plane") {
      const std::string plane = value.cast<std::string>();
      const auto a = io::ValueOf(solvers::kPlaneAssumptionNames, plane);
      if (!a)
        throw std::invalid_argument("local term plane = \"" + plane +
                                    "\": must be \"strain\" or \"stress\"");
      p.plane = *a;
    } else if (k == "youngs_modulus_Pa" || k == "poisson_ratio" || k == "depth_m") {
      const auto pair = value.cast<std::vector<double>>();
      if (pair.size() != 2)
        throw std::invalid_argument("local term " + k + ": must give both bodies' values (2)");
      for (int b = 0; b < 2; ++b) {
        const double v = pair[static_cast<std::size_t>(b)];
        if (k == "youngs_modulus_Pa") p.body[b].youngs_modulus = v;
        if (k == "poisson_ratio") p.body[b].poisson_ratio = v;
        if (k == "depth_m") p.body[b].depth = v;
      }
    } else {
      throw std::invalid_argument(
          "local term key " + k +
          ": unknown (enabled, face_width_m, reduced_radius_m, plane, youngs_modulus_Pa, "
          "poisson_ratio, depth_m)");
    }
  }
  return p;
}

py::dict LocalTermDict(const solvers::LocalTermParameters& p) {
  py::dict d;
  d["enabled"] = p.enabled;
  d["face_width_m"] = p.face_width;
  d["reduced_radius_m"] = p.reduced_radius;
  d["plane"] = io::NameOf(solvers::kPlaneAssumptionNames, p.plane);
  d["youngs_modulus_Pa"] = py::make_tuple(p.body[0].youngs_modulus, p.body[1].youngs_modulus);
  d["poisson_ratio"] = py::make_tuple(p.body[0].poisson_ratio, p.body[1].poisson_ratio);
  d["depth_m"] = py::make_tuple(p.body[0].depth, p.body[1].depth);
  return d;
}

ProblemPtr MakeProblem(const Eigen::MatrixXd& c, const Eigen::VectorXd& overlap,
                       std::optional<Eigen::MatrixXd> g, std::optional<Eigen::VectorXd> w,
                       std::optional<Eigen::MatrixXd> k, std::optional<py::list> local,
                       const std::string& name, std::vector<std::string> contact_labels,
                       std::vector<std::string> multiplier_labels) {
  solvers::ContactProblemData d;
  d.name = name;
  d.compliance = c;
  d.overlap = overlap;
  d.equality_matrix = g ? *g : Eigen::MatrixXd(0, c.cols());
  d.equality_rhs = w ? *w : Eigen::VectorXd(0);
  if (k) d.support_stiffness = *k;
  if (local)
    for (const auto& item : *local) d.local.push_back(LocalTermOf(item.cast<py::dict>()));
  d.contact_labels = std::move(contact_labels);
  d.multiplier_labels = std::move(multiplier_labels);
  return std::make_shared<Problem>(std::move(d));
}

py::object Solve(const Problem& problem, const std::string& backend, double tolerance,
                 int max_iterations, double time_limit_s, bool polish,
                 std::optional<Eigen::VectorXd> force_N, std::optional<Eigen::VectorXd> multiplier,
                 const std::map<std::string, std::string>& options) {
  // The rules of the program's --tol and of the solve's other limits (run_arguments.hpp).
  transmission::CheckArgument(transmission::ContactArguments::kTolerance, tolerance);
  transmission::CheckArgument("max_iterations", max_iterations, transmission::kContactIterations);
  transmission::CheckArgument("time_limit_s", time_limit_s, transmission::kContactTimeLimitS);
  solvers::ContactOptions o;
  o.tolerance = tolerance;
  o.max_iterations = max_iterations;
  o.time_limit = time_limit_s;
  o.polish = polish;
  o.backend_options = options;
  solvers::ContactSolution solution;
  if (force_N || multiplier) {
    o.warm_start = true;
    solution.force = force_N ? *force_N : Eigen::VectorXd::Zero(problem.num_contacts());
    solution.multiplier =
        multiplier ? *multiplier : Eigen::VectorXd::Zero(problem.num_equalities());
  }
  o.Validate();
  const std::unique_ptr<solvers::ContactSolver> solver =
      solvers::MakeContactSolver(BackendOf(backend));
  solvers::ContactReport r;
  {
    py::gil_scoped_release release;
    r = solver->Solve(problem, o, &solution);
  }
  py::dict f;
  f["backend"] = solvers::BackendName(r.backend);
  f["status"] = solvers::StatusName(r.status);
  f["converged"] = r.status == solvers::ContactStatus::kConverged;
  f["message"] = r.message;
  f["iterations"] = r.iterations;
  f["backend_code"] = r.backend_code;
  f["solve_s"] = r.solve_seconds;
  f["total_s"] = r.total_seconds;
  f["residual"] = r.residual.total;
  f["residual_complementarity"] = r.residual.complementarity;
  f["residual_equilibrium"] = r.residual.equilibrium;
  f["active_contacts"] = r.active_contacts;
  f["polished"] = r.polished;
  f["force_N"] = Array(
      std::vector<double>(solution.force.data(), solution.force.data() + solution.force.size()));
  f["multiplier"] = Array(std::vector<double>(
      solution.multiplier.data(), solution.multiplier.data() + solution.multiplier.size()));
  return Result(f);
}

solvers::ContactSolution SolutionOf(const Problem& problem, const Eigen::VectorXd& force_N,
                                    std::optional<Eigen::VectorXd> multiplier) {
  solvers::ContactSolution s;
  s.force = force_N;
  s.multiplier = multiplier ? *multiplier : Eigen::VectorXd::Zero(problem.num_equalities());
  return s;
}

// The contact problem as a Python class: its data, gaps, potential and local terms.
void BindContactProblem(py::module_& m) {
  py::class_<Problem, ProblemPtr>(m, "ContactProblem", R"doc(
A contact problem (docs/model.md §3), validated on construction (ValueError naming the field):
find forces F >= 0 [N] and multipliers λ with
  g = C F + u_local(F) − δ0 − Gᵀλ >= 0,  Fᵀg = 0,  G F + K λ = W.

Parameters
----------
compliance_m_per_N : numpy.ndarray
    C (N, N) [m/N], symmetric positive definite.
overlap_m : numpy.ndarray
    δ0 (N,) [m] (> 0 interpenetration).
equality_matrix : numpy.ndarray or None, default None
    G (m, N) [-] for force rows, [m] for moment rows.
equality_rhs : numpy.ndarray or None, default None
    W (m,) [N] or [N·m].
support_stiffness : numpy.ndarray or None, default None
    K (m, m) [N/m] or [N·m/rad] (None: 0, hard equalities).
local_terms : list of dict or None, default None
    N dicts {face_width_m, reduced_radius_m, plane ("strain", "stress"), youngs_modulus_Pa (E1,
    E2), poisson_ratio (ν1, ν2), depth_m (h1, h2), enabled}.
name : str, default ""
    Free text.
contact_labels, multiplier_labels : list of str, default []
    Free text per contact and per multiplier.

Raises
------
ValueError
    A field of the wrong shape or value (its name).)doc")
      .def(py::init(&MakeProblem), py::arg("compliance_m_per_N"), py::arg("overlap_m"),
           py::kw_only(), py::arg("equality_matrix") = py::none(),
           py::arg("equality_rhs") = py::none(), py::arg("support_stiffness") = py::none(),
           py::arg("local_terms") = py::none(), py::arg("name") = "",
           py::arg("contact_labels") = std::vector<std::string>{},
           py::arg("multiplier_labels") = std::vector<std::string>{},
           "A contact problem; the parameters as the class's.")
      .def_property_readonly("name", &Problem::name)
      .def_property_readonly("num_contacts", &Problem::num_contacts, "N [-]")
      .def_property_readonly("num_equalities", &Problem::num_equalities, "m [-]")
      .def_property_readonly("compliance_m_per_N", &Problem::compliance, "C (N, N) [m/N]")
      .def_property_readonly("overlap_m", &Problem::overlap, "δ0 (N,) [m]")
      .def_property_readonly("equality_matrix", &Problem::equality_matrix, "G (m, N)")
      .def_property_readonly("equality_rhs", &Problem::equality_rhs, "W (m,) [N] or [N·m]")
      .def_property_readonly("support_stiffness", &Problem::support_stiffness, "K (m, m)")
      .def_property_readonly(
          "local_terms",
          [](const Problem& p) {
            py::list l;
            for (const auto& t : p.data().local) l.append(LocalTermDict(t));
            return l;
          },
          "The local terms as dicts (empty: none).")
      .def("gap_m", &Problem::Gap, py::arg("force_N"), py::arg("multiplier"),
           R"doc(
The gaps g = C F + u_local(F) − δ0 − Gᵀλ.

Parameters
----------
force_N : numpy.ndarray
    F (N,) [N].
multiplier : numpy.ndarray
    λ (m,) [m] or [rad].

Returns
-------
numpy.ndarray
    g (N,) [m].)doc")
      .def("potential_J", &Problem::Potential, py::arg("force_N"),
           R"doc(
The potential Φ(F) (without the support term).

Parameters
----------
force_N : numpy.ndarray
    F (N,) >= 0 [N].

Returns
-------
float
    Φ [J].)doc")
      .def("local_approach_m", &Problem::LocalApproach, py::arg("force_N"),
           R"doc(
The local approach u_local(F) per contact.

Parameters
----------
force_N : numpy.ndarray
    The contact forces F (N,) >= 0 [N].

Returns
-------
numpy.ndarray
    u_local (N,) [m].)doc")
      .def("validity_limit_force_N", &Problem::ValidityLimitForce, py::arg("contact"),
           R"doc(
The force at which a contact's Hertz half-width reaches its depth h.

Parameters
----------
contact : int
    The contact j, 0..N-1.

Returns
-------
float
    The force [N] (inf: no local term).)doc");
}

// A comparison's sink in Python: nothing streamed (the record holds every run); a Ctrl-C stops
// the comparison at its next run.
class CancellableComparison final : public solvers::ComparisonSink {
 public:
  explicit CancellableComparison(const CancelToken* token) : token_(token) {}
  void Failure(const std::string&) override {}
  void Run(const solvers::ComparisonRun&) override {
    if (token_->cancelled) throw Cancelled();
  }

 private:
  const CancelToken* token_;
};

py::object CompareBackends(const std::vector<std::string>& inputs, double tolerance, int repeats,
                           std::optional<std::vector<std::string>> backends) {
  // The rules of the program's --tol and --repeat (run_arguments.hpp).
  transmission::CheckArgument(transmission::ContactArguments::kTolerance, tolerance);
  transmission::CheckArgument(transmission::ContactArguments::kRepeats, repeats);
  solvers::ComparisonRequest request;
  request.inputs = inputs;
  request.options.tolerance = tolerance;
  request.repeats = repeats;
  if (backends) {
    request.backends.clear();
    for (const std::string& name : *backends) request.backends.push_back(BackendOf(name));
  }
  CancelToken token;
  const solvers::ComparisonRecord record = RunReleased(token, [&] {
    CancellableComparison sink(&token);
    return solvers::RunComparison(request, sink);
  });
  py::dict f;
  f["failures"] = record.failures;
  // The program's JSON (`epicycle contact compare --json`), its one serialisation.
  f["record"] = JsonToPython(report::RecordJson(record));
  return Result(f);
}

// The comparison of back ends over problem files.
void BindComparison(py::module_& m) {
  m.def("compare_backends", &CompareBackends, py::arg("inputs"), py::kw_only(),
        py::arg("tolerance") = solvers::ContactOptions().tolerance,
        py::arg("repeats") = solvers::kDefaultComparisonRepeats, py::arg("backends") = py::none(),
        R"doc(
Every back end on every problem file against each problem's reference, the active-set Newton at
1e-12 (`epicycle contact compare`, docs/solvers.md). A run that does not converge is a result:
it is listed in failures (the program exits 1).

Parameters
----------
inputs : list of str
    Problem files or folders of them (JSON, verification/data/contact's format).
tolerance : float, default 1e-10
    Every back end's tolerance on the nondimensional residual [-], in (0, 1].
repeats : int, default 5
    Solves per (back end, problem), the median time reported [-], in [1, 1000].
backends : list of str or None, default None
    The back ends, in the runs' order (None: every available one, contact_backends()).

Returns
-------
Result
    failures (each failed run: back end, problem, file, status); record: the comparison's
    record, the keys and values of `epicycle contact compare --json` (docs/records.md).

Raises
------
ValueError
    Bad input (the argument's name, value and rule; a file that is not a problem file).)doc");
}

// The solvers: one back end, the residuals and differences of an answer, the files of problems.
void BindContactSolvers(py::module_& m) {
  const solvers::ContactOptions options;  // the library's defaults, the keywords' too
  m.def("solve_contact", &Solve, py::arg("problem"), py::arg("backend") = "newton", py::kw_only(),
        py::arg("tolerance") = options.tolerance,
        py::arg("max_iterations") = options.max_iterations,
        py::arg("time_limit_s") = options.time_limit, py::arg("polish") = options.polish,
        py::arg("force_N") = py::none(), py::arg("multiplier") = py::none(),
        py::arg("options") = std::map<std::string, std::string>{}, R"doc(
Solves a contact problem with a back end; the driver judges every back end by one residual
(docs/solvers.md). A status other than converged is a result, not an exception.

Parameters
----------
problem : ContactProblem
    The problem.
backend : str, default "newton"
    "newton", "ipopt", "nlopt-slsqp", "nlopt-lbfgs", "nlopt-auglag" (epicycle.contact_backends()).
tolerance : float, default 1e-10
    On the nondimensional residual [-], in (0, 1].
max_iterations : int, default 200
    [-], in [1, 10^6].
time_limit_s : float, default 60
    [s], in (0, 86400].
polish : bool, default False
    A labelled active-set polish step.
force_N : numpy.ndarray or None, default None
    Warm start F (N,) [N].
multiplier : numpy.ndarray or None, default None
    Warm start λ (m,) [m] or [rad].
options : dict of str to str, default {}
    Back-end knobs ("ipopt.mu_strategy": "adaptive", ...).

Returns
-------
Result
    force_N (N,) [N], multiplier (m,) [m] or [rad], status ("converged", "converged-inaccurate",
    "iteration-limit", ...), converged (status converged), message, iterations, backend_code,
    residual, residual_complementarity, residual_equilibrium [-], active_contacts, solve_s,
    total_s [s], polished, backend.

Raises
------
ValueError
    Bad input (the argument's name, value and rule).)doc");
  m.def(
      "contact_residuals",
      [](const Problem& problem, const Eigen::VectorXd& force_N,
         std::optional<Eigen::VectorXd> multiplier) {
        const solvers::ContactResiduals r =
            solvers::EvaluateResiduals(problem, SolutionOf(problem, force_N, multiplier));
        py::dict f;
        f["residual"] = r.total;
        f["residual_complementarity"] = r.complementarity;
        f["residual_equilibrium"] = r.equilibrium;
        return Result(f);
      },
      py::arg("problem"), py::arg("force_N"), py::arg("multiplier") = py::none(), R"doc(
The residuals every back end is judged by, of any answer (e.g. from a solver of one's own),
nondimensional as solve_contact's report (docs/solvers.md).

Parameters
----------
problem : ContactProblem
    The problem.
force_N : numpy.ndarray
    F (N,) [N].
multiplier : numpy.ndarray or None, default None
    λ (m,) [m] or [rad] (None: zeros).

Returns
-------
Result
    residual, residual_complementarity (the natural map), residual_equilibrium [-].

Raises
------
ValueError
    Arrays of the wrong length.)doc");
  m.def(
      "compare_solutions",
      [](const Problem& problem, const Eigen::VectorXd& force_N,
         std::optional<Eigen::VectorXd> multiplier, const Eigen::VectorXd& reference_force_N,
         std::optional<Eigen::VectorXd> reference_multiplier) {
        const solvers::SolutionDifference d =
            solvers::CompareSolutions(problem, SolutionOf(problem, force_N, multiplier),
                                      SolutionOf(problem, reference_force_N, reference_multiplier));
        py::dict f;
        f["force"] = d.force;
        f["multiplier"] = d.multiplier;
        f["displacement"] = d.displacement;
        return Result(f);
      },
      py::arg("problem"), py::arg("force_N"), py::arg("multiplier"), py::arg("reference_force_N"),
      py::arg("reference_multiplier"), R"doc(
Relative differences of a solution from a reference (docs/solvers.md): force
‖F − F_ref‖∞ / max(‖F_ref‖∞, F*), multiplier (as rigid displacements) and displacement
‖Gᵀ(λ − λ_ref)‖∞ / max(‖Gᵀλ_ref‖∞, ℓ*).

Parameters
----------
problem : ContactProblem
    The problem.
force_N, reference_force_N : numpy.ndarray
    F and F_ref (N,) [N].
multiplier, reference_multiplier : numpy.ndarray or None
    λ and λ_ref (m,) [m] or [rad] (None: zeros).

Returns
-------
Result
    force, multiplier, displacement [-].

Raises
------
ValueError
    Arrays of the wrong length.)doc");
  m.def(
      "contact_backends",
      [](bool available_only) {
        std::vector<std::string> names;
        for (solvers::Backend b :
             available_only ? solvers::AvailableBackends() : solvers::AllBackends())
          names.push_back(solvers::BackendName(b));
        return names;
      },
      py::kw_only(), py::arg("available_only") = true, R"doc(
The names of the contact back ends.

Parameters
----------
available_only : bool, default True
    Only those compiled in (False: every back end the library knows).

Returns
-------
list of str
    Back-end names, as solve_contact takes them.)doc");
  m.def(
      "read_contact_problem",
      [](const std::string& path) {
        solvers::ContactProblemFile file = solvers::ReadContactProblemFile(path);
        py::dict f;
        f["category"] = file.category;
        f["description"] = file.description;
        f["provenance"] = file.provenance;
        if (file.expected) {
          f["expected_force_N"] =
              Array(std::vector<double>(file.expected->force.data(),
                                        file.expected->force.data() + file.expected->force.size()));
          f["expected_multiplier"] = Array(std::vector<double>(
              file.expected->multiplier.data(),
              file.expected->multiplier.data() + file.expected->multiplier.size()));
        } else {
          f["expected_force_N"] = py::none();
          f["expected_multiplier"] = py::none();
        }
        f["problem"] = std::make_shared<Problem>(std::move(file.data));
        return Result(f);
      },
      py::arg("path"), R"doc(
Reads a contact problem file (JSON, the collection's format: verification/data/contact).

Parameters
----------
path : str
    The file.

Returns
-------
Result
    problem (ContactProblem), category, description, provenance, expected_force_N [N] and
    expected_multiplier ([m] or [rad]; an independent solution) or None.

Raises
------
ValueError
    A missing or malformed file (its path and the field).)doc");
}

}  // namespace

void BindContact(py::module_& m) {
  BindContactProblem(m);
  BindContactSolvers(m);
  BindComparison(m);
}

}  // namespace epicycle::python
