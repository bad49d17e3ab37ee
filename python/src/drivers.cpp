// The tolerance studies of studies/: a study file's cases run on threads, their rows and summary.
#include <atomic>
#include <filesystem>
#include <optional>
#include <random>
#include <thread>

#include "common.hpp"
#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/study.hpp"
#include "epicycle/studies/study_summary.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/run_arguments.hpp"

namespace epicycle::python {

namespace {

// A rows file of its own in the temporary folder, removed with the object (a study run without a
// rows file of the caller's).
class TemporaryRows {
 public:
  TemporaryRows() {
    static std::atomic<unsigned> counter{0};
    std::random_device random;
    dir_ = std::filesystem::temp_directory_path() /
           ("epicycle-study-" + std::to_string(random()) + "-" + std::to_string(++counter));
    std::filesystem::create_directories(dir_);
  }
  ~TemporaryRows() {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  TemporaryRows(const TemporaryRows&) = delete;
  TemporaryRows& operator=(const TemporaryRows&) = delete;
  std::string path() const { return (dir_ / "rows.csv").string(); }

 private:
  std::filesystem::path dir_;
};

py::object SampleObject(const studies::SampleSummary& s);

py::object Study(const std::string& path, std::optional<std::string> text, int threads,
                 long max_cases, std::optional<std::string> rows_file,
                 std::optional<std::string> cache_dir, py::object progress) {
  transmission::CheckArgument("threads", threads, transmission::kThreadsOrZero);
  if (max_cases >= 0)  // < 0: every case
    transmission::CheckArgument("max_cases", static_cast<double>(max_cases),
                                transmission::kStudyCases);
  const studies::StudySpec study =
      text ? studies::ParseStudy(*text, path, std::filesystem::path(path).parent_path().string())
           : studies::ReadStudy(path);
  CancelToken token;
  const Progress report(std::move(progress), &token);
  const studies::RunReport run = RunReleased(token, [&] {
    TemporaryRows temporary;
    studies::RunOptions o;
    o.rows_file = rows_file ? *rows_file : temporary.path();
    o.cache_directory = cache_dir ? *cache_dir : transmission::DefaultCacheDirectory();
    o.threads =
        threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    o.max_new_cases = max_cases;
    o.on_row = [&](const studies::CaseRow&, long rows, long total) { report(rows, total); };
    return studies::RunStudy(study, o);
  });
  const std::vector<std::string> columns = study.Columns();
  const auto count = static_cast<py::ssize_t>(run.rows.size());
  const auto width = static_cast<py::ssize_t>(columns.size());
  std::vector<long> id;
  std::vector<double> values, kg, kgm, lmin, lmax, te, orbit;
  std::vector<int> positions, converged;
  std::vector<char> ok;
  py::list message, lines;
  for (const studies::CaseRow& r : run.rows) {
    id.push_back(r.id);
    values.insert(values.end(), r.values.begin(), r.values.end());
    ok.push_back(r.ok);
    message.append(r.message);
    positions.push_back(r.positions);
    converged.push_back(r.converged);
    kg.push_back(r.k_gamma);
    kgm.push_back(r.k_gamma_mean);
    lmin.push_back(r.lsr_min);
    lmax.push_back(r.lsr_max);
    te.push_back(r.te_peak_to_peak);
    orbit.push_back(r.sun_orbit);
    lines.append(r.Format());
  }
  const studies::StudySummary sum = studies::SummariseStudy(study, run.rows);
  py::dict summary;
  summary["cases"] = sum.cases;
  summary["failed"] = sum.failed;
  summary["k_gamma"] = SampleObject(sum.k_gamma);
  summary["k_gamma_mean"] = SampleObject(sum.k_gamma_mean);
  summary["te_peak_to_peak_urad"] = SampleObject(sum.te_peak_to_peak);
  summary["sun_orbit_um"] = SampleObject(sum.sun_orbit);
  summary["spearman_k_gamma"] = Array(std::vector<double>(sum.spearman));
  py::dict f;
  f["study"] = study.name;
  f["cases"] = study.Cases();
  f["columns"] = columns;
  f["case_id"] = Array(std::move(id));
  f["values"] = Array2(std::move(values), count, width);
  f["ok"] = BoolArray(ok);
  f["message"] = message;
  f["positions"] = Array(std::move(positions));
  f["converged"] = Array(std::move(converged));
  f["k_gamma"] = Array(std::move(kg));
  f["k_gamma_mean"] = Array(std::move(kgm));
  f["lsr_min"] = Array(std::move(lmin));
  f["lsr_max"] = Array(std::move(lmax));
  f["te_peak_to_peak_urad"] = Array(std::move(te));
  f["sun_orbit_um"] = Array(std::move(orbit));
  f["header"] = studies::RowHeader(study);
  f["rows_csv"] = lines;
  f["resumed"] = run.resumed;
  f["computed"] = run.computed;
  f["seconds"] = run.seconds;
  f["summary"] = Result(summary);
  f["warnings"] = study.warnings;
  return Result(f);
}

py::object SampleObject(const studies::SampleSummary& s) {
  std::vector<double> level, value, lower, upper;
  for (const studies::Percentile& p : s.percentiles) {
    level.push_back(p.p);
    value.push_back(p.value);
    lower.push_back(p.lower);
    upper.push_back(p.upper);
  }
  py::dict f;
  f["count"] = s.count;
  f["mean"] = s.mean;
  f["standard_deviation"] = s.standard_deviation;
  f["mean_lower"] = s.mean_lower;
  f["mean_upper"] = s.mean_upper;
  f["min"] = s.min;
  f["max"] = s.max;
  f["percentile_level"] = Array(std::move(level));
  f["percentile"] = Array(std::move(value));
  f["percentile_lower"] = Array(std::move(lower));
  f["percentile_upper"] = Array(std::move(upper));
  f["confidence_level"] = s.level;
  return Result(f);
}

}  // namespace

void BindStudies(py::module_& m) {
  m.def(
      "study",
      [](const std::string& path, std::optional<std::string> text, int threads, long max_cases,
         std::optional<std::string> rows_file, std::optional<std::string> cache_dir,
         py::object progress) {
        return Study(path, text, threads, max_cases, rows_file, cache_dir, std::move(progress));
      },
      py::arg("path"), py::arg("text") = py::none(), py::arg("threads") = 0,
      py::arg("max_cases") = -1, py::arg("rows_file") = py::none(),
      py::arg("cache_dir") = py::none(), py::arg("progress") = py::none(), R"doc(
A tolerance study (`epicycle study`; docs/studies.md): every case a quasi-static sweep of the base
scene with its sampled errors, on threads.

path: the study file (TOML); text: the study's text instead (path then names it in messages and
  its folder resolves the scene path); threads: workers (0: every core); max_cases: stop after
  this many new cases (< 0: all); rows_file: a rows CSV to write and resume (None: a temporary
  one, removed); cache_dir as quasistatic; progress(rows, total).
Returns Result with per case (sorted by case_id): case_id, values (cases, columns) [the columns'
units: _um µm, _deg deg, _Nm N·m], ok, message, positions, converged, k_gamma [-], k_gamma_mean
[-], lsr_min, lsr_max [-], te_peak_to_peak_urad [µrad], sun_orbit_um [µm]; columns, header and
rows_csv (each row as the rows file has it); summary (cases, failed, k_gamma, k_gamma_mean,
te_peak_to_peak_urad, sun_orbit_um: count, mean, percentiles with confidence intervals;
spearman_k_gamma per column); study, cases, resumed, computed, seconds [s], warnings.)doc");
}

}  // namespace epicycle::python
