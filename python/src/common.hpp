// What every binding file shares: numpy arrays from C++ containers, the package's result and
// exception types, and running a computation with the GIL released so that other Python threads
// run and Ctrl-C stops it (docs/python.md, "Threads and interrupts").
#pragma once

#include <atomic>
#include <chrono>
#include <exception>
#include <future>
#include <memory>
#include <string>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/run_status.hpp"

namespace epicycle::python {

namespace py = pybind11;

/// A range's name as a keyword's default ("cycle", "planet": transmission::kRunRangeNames).
inline std::string RangeName(transmission::RunRange range) {
  return io::NameOf(transmission::kRunRangeNames, range);
}

/// A 1-D numpy array that takes over `values` (no copy: the vector lives on in the array's base).
template <typename T>
py::array_t<T> Array(std::vector<T>&& values) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule base(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(static_cast<py::ssize_t>(owned->size()), owned->data(), base);
}

/// A numpy array of `shape` over `values` (row-major, taken over as Array).
template <typename T>
py::array_t<T> ArrayOfShape(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule base(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(std::move(shape), owned->data(), base);
}

/// A 2-D numpy array rows × cols over `values` (row-major, taken over as Array).
template <typename T>
py::array_t<T> Array2(std::vector<T>&& values, py::ssize_t rows, py::ssize_t cols) {
  return ArrayOfShape(std::move(values), {rows, cols});
}

/// Python strings of repeated C++ strings (mesh names, kinds, statuses), each made once.
class Interned {
 public:
  const py::str& operator()(const std::string& s) {
    auto it = made_.find(s);
    if (it == made_.end()) it = made_.emplace(s, py::str(s)).first;
    return it->second;
  }

 private:
  std::unordered_map<std::string, py::str> made_;
};

/// A numpy bool array from flags.
py::array_t<bool> BoolArray(const std::vector<char>& flags);

/// epicycle.Result(**fields): the plain object every driver returns.
py::object Result(const py::dict& fields);

/// Raises epicycle.ComputationError(message) with `result` (what was computed) as its `.result`.
[[noreturn]] void RaiseComputationError(const std::string& message, const py::object& result);
/// Raises the ComputationError subclass of a run's `status` (epicycle.ContactFailure,
/// IntegratorFailure, TimeLimitReached, GeometryFailure) with `message` and `result`.
[[noreturn]] void RaiseRunFailure(transmission::RunStatus status, const std::string& message,
                                  const py::object& result);
/// Raises for the failed parts of a run (a sweep's speeds, a study's cases) with the statuses
/// `failed`: the subclass of their status when they share one (RaiseRunFailure), else
/// ComputationError.
[[noreturn]] void RaiseFailures(const std::vector<transmission::RunStatus>& failed,
                                const std::string& message, const py::object& result);

/// A JSON document as Python objects (through the json module: the report's own keys and units,
/// the numbers as the summary JSON files hold them).
py::object JsonToPython(const nlohmann::json& j);

/// The back end of a name ("newton", "ipopt", ...). @throws std::invalid_argument (ValueError).
solvers::Backend BackendOf(const std::string& name);

/// Set by the waiting Python thread when Ctrl-C arrives; the computation's callbacks stop it.
struct CancelToken {
  std::atomic<bool> cancelled{false};
};

/// Thrown from a computation's callback once it is cancelled (never reaches Python).
struct Cancelled : std::exception {
  const char* what() const noexcept override { return "cancelled"; }
};

/// A Python progress callable progress(done, total), called from the computation's callbacks
/// (any thread, with the GIL taken for the call); None: only the cancellation check. A Python
/// exception it raises stops the computation and is re-raised.
class Progress {
 public:
  Progress(py::object callback, CancelToken* token)
      : callback_(std::move(callback)), token_(token) {}
  void operator()(long done, long total) const {
    if (token_->cancelled) throw Cancelled();
    if (callback_.is_none()) return;
    py::gil_scoped_acquire gil;
    callback_(done, total);
  }
  /// For a computation that reports no progress: throws Cancelled once cancelled.
  void Check() const {
    if (token_->cancelled) throw Cancelled();
  }

 private:
  py::object callback_;
  CancelToken* token_;
};

/// Runs `work` (pure C++, no Python object) on a worker thread with the GIL released; the calling
/// thread waits and checks for signals every 50 ms (Ctrl-C in the main thread: the token is set,
/// the computation stops at its next callback, KeyboardInterrupt is raised). The work's own
/// exception is rethrown here (std::invalid_argument → ValueError).
template <typename F>
auto RunReleased(CancelToken& token, F&& work) -> decltype(work()) {
  using R = decltype(work());
  std::packaged_task<R()> task(std::forward<F>(work));
  std::future<R> done = task.get_future();
  {
    py::gil_scoped_release release;
    std::thread worker(std::move(task));
    while (done.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {
        token.cancelled = true;
        py::error_already_set interrupt;
        {
          py::gil_scoped_release wait;
          worker.join();
        }
        throw interrupt;
      }
    }
    worker.join();
  }
  return done.get();
}

// The parts of the module, one per file.
void BindScene(py::module_& m);    // scene.cpp
void BindStage(py::module_& m);    // stage.cpp: geometry, contacts, mesh stiffness, quasi-static
void BindDynamicRun(py::module_& m);      // dynamic.cpp: a run in time
void BindModes(py::module_& m);           // modes.cpp: natural modes
void BindSpeedSweep(py::module_& m);      // speed_sweep.cpp: speed sweeps and their grids
void BindPeriodicBranch(py::module_& m);  // periodic_branch.cpp: branches of periodic orbits
void BindStudies(py::module_& m);  // drivers.cpp: tolerance studies
void BindContact(py::module_& m);  // contact.cpp: the contact core
void BindStream(py::module_& m);   // stream.cpp: the quasi-static sweep one position at a time

}  // namespace epicycle::python
