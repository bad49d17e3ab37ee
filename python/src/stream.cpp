// The quasi-static sweep one position at a time (epicycle.quasistatic_positions): the library's
// streaming sweep (transmission::SweepEach) on a worker thread without the GIL, its results handed
// through a bounded queue to the Python iterator, which takes them with the GIL; nothing grows
// with the number of positions (docs/python.md, "Streaming a sweep").
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include "common.hpp"
#include "scene.hpp"
#include "sweep.hpp"

namespace epicycle::python {

namespace {

// Positions converted and waiting for Python at most: the worker waits when the queue is full,
// so the memory is this many rows plus the library's in-flight results
// (transmission::kSweepInFlight), whatever the number of positions.
constexpr std::size_t kQueued = 256;

class PositionStream {
 public:
  PositionStream(SweepRequest request, const std::optional<std::string>& cache_dir)
      : request_(std::move(request)), record_(py::module_::import("epicycle").attr("Result")) {
    CancelToken token;
    rig_ = RunReleased(token, [&] { return request_.scene->Rig(cache_dir, "quasistatic"); });
    model_ = std::make_unique<transmission::StageModel>(rig_->Model(request_.local_terms));
    angles_ = request_.Angles(rig_->stage);
    planets_ = rig_->stage.planets();
    with_friction_ = request_.options.friction.law != transmission::FrictionLaw::kOff;
    worker_ = std::thread([this] { Work(); });
  }
  ~PositionStream() { Stop(); }
  PositionStream(const PositionStream&) = delete;
  PositionStream& operator=(const PositionStream&) = delete;

  long size() const { return std::ssize(angles_); }
  int planets() const { return planets_; }

  // The next position's record; StopIteration after the last; the sweep's own exception (bad
  // input, a failed table build) once its positions before it are taken.
  py::object Next() {
    std::optional<std::pair<int, PositionRow>> item;
    std::exception_ptr error;
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> lock(mutex_);
      while (queue_.empty() && !finished_) {
        if (changed_.wait_for(lock, std::chrono::milliseconds(50)) == std::cv_status::timeout) {
          lock.unlock();
          {
            py::gil_scoped_acquire gil;
            if (PyErr_CheckSignals() != 0) {  // Ctrl-C: the sweep stops, KeyboardInterrupt
              py::error_already_set interrupt;
              Cancel();
              throw interrupt;
            }
          }
          lock.lock();
        }
      }
      if (!queue_.empty()) {
        item = std::move(queue_.front());
        queue_.pop_front();
        changed_.notify_all();
      } else {
        error = std::exchange(error_, nullptr);
      }
    }
    if (error) std::rethrow_exception(error);
    if (!item) throw py::stop_iteration();
    return Record(item->first, item->second);
  }

  // Stops the sweep (the positions being solved finish first) and lets its thread go.
  void Stop() {
    Cancel();
    if (worker_.joinable()) worker_.join();
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.clear();  // the iterator ends here
    error_ = nullptr;
  }

 private:
  void Cancel() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      cancelled_ = true;
    }
    changed_.notify_all();
  }

  void Work() {
    try {
      transmission::SweepEach(
          *model_, rig_->scene.loads, static_cast<int>(angles_.size()),
          [this](int k) { return angles_[static_cast<std::size_t>(k)]; }, request_.options,
          [this](const transmission::PositionResult& r, int k) {
            PositionRow row = RowOf(r, planets_, with_friction_);
            std::unique_lock<std::mutex> lock(mutex_);
            changed_.wait(lock, [this] { return cancelled_ || queue_.size() < kQueued; });
            if (cancelled_) throw Cancelled();
            queue_.emplace_back(k, std::move(row));
            changed_.notify_all();
          });
    } catch (const Cancelled&) {
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      finished_ = true;
    }
    changed_.notify_all();
  }

  py::object Record(int k, const PositionRow& w) {
    py::dict f;
    f["index"] = k;
    f["carrier_deg"] = w.carrier_deg;
    f["converged"] = w.converged;
    f["lsr"] = Array(std::vector<double>(w.lsr));
    f["load_sharing_factor"] = Array(std::vector<double>(w.factor));
    f["k_gamma"] = w.k_gamma;
    f["te_urad"] = w.te_rad * 1e6;  // as RunColumns (epicycle.quasistatic's arrays)
    f["sun_x_um"] = w.sun_x_m * 1e6;
    f["sun_y_um"] = w.sun_y_m * 1e6;
    f["geometric_iterations"] = w.geometric_iterations;
    f["contact_iterations"] = w.contact_iterations;
    f["warm_started"] = w.warm_started;
    f["residual"] = w.residual;
    f["status"] = names_(w.status);
    f["active_contacts"] = w.active_contacts;
    f["contacts"] = w.contacts;
    f["solve_ms"] = w.solve_ms;
    f["message"] = names_(w.message);
    if (with_friction_) {
      f["friction_power_W"] = w.friction_power_W;
      f["input_power_W"] = w.input_power_W;
      f["output_power_W"] = w.output_power_W;
      f["efficiency"] = w.efficiency;
      f["force_change"] = w.force_change;
    }
    return record_(**f);
  }

  SweepRequest request_;
  py::object record_;  // epicycle.Result
  std::shared_ptr<const StageRig> rig_;
  std::unique_ptr<transmission::StageModel> model_;
  std::vector<double> angles_;
  int planets_ = 0;
  bool with_friction_ = false;
  Interned names_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::pair<int, PositionRow>> queue_;
  bool finished_ = false, cancelled_ = false;
  std::exception_ptr error_;
  std::thread worker_;  // last: started once the members it uses exist
};

}  // namespace

void BindStream(py::module_& m) {
  const transmission::QuasiStaticRequest& qs = QuasiStaticDefaults();  // the keywords' defaults
  py::class_<PositionStream>(m, "QuasiStaticPositions", R"doc(
An iterator over the positions of a quasi-static sweep, one record per position in the order of
the positions (epicycle.quasistatic_positions makes it).

The sweep runs on worker threads without the GIL while Python takes the records; at most a
bounded number of positions is held (the library's in-flight results and a queue of 256), so a
sweep of 10^6 positions runs in the memory of a few thousand. Leaving the loop early (break, an
exception, close()) stops the sweep.)doc")
      .def("__iter__", [](py::object self) { return self; })
      .def("__next__", &PositionStream::Next, R"doc(
The next position's record.

Returns
-------
Result
    The position's values (epicycle.quasistatic_positions).

Raises
------
StopIteration
    After the last position.
ValueError
    The sweep's bad input found once it started.)doc")
      .def("__len__", &PositionStream::size, "Positions of the sweep [-].")
      .def_property_readonly("planets", &PositionStream::planets, "Planets n [-].")
      .def(
          "close", [](PositionStream& s) {
            py::gil_scoped_release release;
            s.Stop();
          },
          "Stops the sweep; the iterator then ends.")
      .def("__enter__", [](py::object self) { return self; })
      .def(
          "__exit__",
          [](PositionStream& s, const py::args&) {
            py::gil_scoped_release release;
            s.Stop();
          },
          R"doc(
Stops the sweep (as close()).

Parameters
----------
*args
    The exception's type, value and traceback (or None).)doc");
  m.def(
      "quasistatic_positions",
      [](const std::shared_ptr<Scene>& s, const std::string& range, int positions, double start_deg,
         std::optional<std::vector<double>> angles_deg, int threads, bool warm_start,
         const std::string& backend, bool local_terms, std::optional<std::string> cache_dir,
         const std::string& friction) {
        return std::make_unique<PositionStream>(
            MakeSweepRequest(s, range, positions, start_deg, std::move(angles_deg), threads,
                             warm_start, backend, local_terms, friction, false, false),
            cache_dir);
      },
      py::arg("scene"), py::kw_only(), py::arg("range") = RangeName(qs.range),
      py::arg("positions") = qs.positions, py::arg("start_deg") = qs.start_deg,
      py::arg("angles_deg") = py::none(), py::arg("threads") = qs.threads,
      py::arg("warm_start") = qs.warm_start, py::arg("backend") = qs.backend,
      py::arg("local_terms") = qs.local_terms, py::arg("cache_dir") = py::none(),
      py::arg("friction") = qs.friction, R"doc(
The quasi-static sweep of epicycle.quasistatic one position at a time, in flat memory
(docs/python.md, "Streaming a sweep"): each record is taken as the sweep computes it.

Parameters
----------
scene : Scene
    A stage scene.
range : str, default "cycle"
    "cycle", "planet", "sun", "revolution" (as quasistatic's).
positions : int, default 0
    Positions over the range [-] (0: 60 per mesh cycle).
start_deg : float, default 0
    Carrier angle of the first position [deg].
angles_deg : list of float or None, default None
    Given carrier angles [deg] instead of range and positions.
threads : int, default 0
    Workers [-] (0: one per core).
warm_start : bool, default True
    Each position from its neighbour.
backend : str, default "newton"
    Contact back end.
local_terms : bool, default True
    False: the structural compliance only.
cache_dir : str or None, default None
    Influence-table cache (as quasistatic's).
friction : str, default "off"
    Friction at rest (as quasistatic's).

Returns
-------
QuasiStaticPositions
    An iterator of one Result per position, in order: index, carrier_deg [deg], converged,
    lsr (n,) [-], load_sharing_factor (n,) [-], k_gamma [-], te_urad [µrad], sun_x_um, sun_y_um
    [µm], geometric_iterations, contact_iterations, warm_started, residual [-], status,
    active_contacts, contacts, solve_ms [ms], message; with friction friction_power_W,
    input_power_W, output_power_W [W], efficiency, force_change [-]. The values are quasistatic's
    for the same arguments, bit for bit.

Raises
------
ValueError
    Bad input (the argument's name, value and rule), before any work.)doc");
}

}  // namespace epicycle::python
