// The module `epicycle._epicycle` (imported by the package epicycle: python/epicycle/__init__.py).
#include <algorithm>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "common.hpp"

namespace epicycle::python {

py::array_t<bool> BoolArray(const std::vector<char>& flags) {
  py::array_t<bool> a(static_cast<py::ssize_t>(flags.size()));
  auto w = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < flags.size(); ++i) w(static_cast<py::ssize_t>(i)) = flags[i] != 0;
  return a;
}

py::object Result(const py::dict& fields) {
  return py::module_::import("epicycle").attr("Result")(**fields);
}

void RaiseComputationError(const std::string& message, const py::object& result) {
  const py::object type = py::module_::import("epicycle").attr("ComputationError");
  const py::object error = type(message, result);
  PyErr_SetObject(type.ptr(), error.ptr());
  throw py::error_already_set();
}

void RaiseRunFailure(transmission::RunStatus status, const std::string& message,
                     const py::object& result) {
  using transmission::RunStatus;
  const char* name = status == RunStatus::kContactFailure      ? "ContactFailure"
                     : status == RunStatus::kIntegratorFailure ? "IntegratorFailure"
                     : status == RunStatus::kTimeLimit         ? "TimeLimitReached"
                     : status == RunStatus::kGeometry          ? "GeometryFailure"
                     : status == RunStatus::kBadSampledValue   ? "BadSampledValue"
                                                               : "ComputationError";
  const py::object type = py::module_::import("epicycle").attr(name);
  const py::object error = type(message, result);
  PyErr_SetObject(type.ptr(), error.ptr());
  throw py::error_already_set();
}

void RaiseFailures(const std::vector<transmission::RunStatus>& failed, const std::string& message,
                   const py::object& result) {
  const bool one = !failed.empty() && std::all_of(failed.begin(), failed.end(), [&](auto s) {
    return s == failed.front();
  });
  if (one) RaiseRunFailure(failed.front(), message, result);
  RaiseComputationError(message, result);
}

py::object JsonToPython(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

solvers::Backend BackendOf(const std::string& name) { return solvers::BackendFromName(name); }

}  // namespace epicycle::python

PYBIND11_MODULE(_epicycle, m) {
  namespace ep = epicycle::python;
  namespace py = pybind11;
  m.doc() = "epicycle's C++ libraries (docs/python.md); use the package `epicycle`.";
  // Bad input (std::invalid_argument) is pybind11's ValueError; a failed computation
  // (std::runtime_error: a quasi-static start that does not converge, every sample of a mesh
  // failed) is epicycle.ComputationError, without a result.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::builtin_exception&) {
      throw;
    } catch (const std::runtime_error& e) {
      const py::object type = py::module_::import("epicycle").attr("ComputationError");
      PyErr_SetObject(type.ptr(), type(e.what()).ptr());
    }
  });
  ep::BindScene(m);
  ep::BindStage(m);
  ep::BindDynamicRun(m);
  ep::BindModes(m);
  ep::BindSpeedSweep(m);
  ep::BindPeriodicBranch(m);
  ep::BindStudies(m);
  ep::BindContact(m);
  ep::BindStream(m);
}
