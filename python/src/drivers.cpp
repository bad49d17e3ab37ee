// The tolerance studies of studies/: a study file's cases run on threads, their rows and summary.
#include <atomic>
#include <filesystem>
#include <optional>
#include <random>
#include <thread>

#include "common.hpp"
#include "epicycle/report/provenance.hpp"
#include "epicycle/report/record_json.hpp"
#include "epicycle/report/study_files.hpp"
#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/shards.hpp"
#include "epicycle/studies/sobol.hpp"
#include "epicycle/studies/study.hpp"
#include "epicycle/studies/study_run.hpp"
#include "epicycle/studies/study_summary.hpp"
#include "integration.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/run_arguments.hpp"
#include "failed_parts.hpp"

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
py::object SobolObject(const studies::SobolEstimate& e);

py::object Study(const std::string& path, std::optional<std::string> text, int threads,
                 long max_cases, std::optional<std::string> rows_file,
                 std::optional<std::string> cache_dir, py::object progress,
                 bool raise_on_failure) {
  transmission::CheckArgument("threads", threads, transmission::kThreadsOrZero);
  if (max_cases >= 0)  // < 0: every case
    transmission::CheckArgument(transmission::StudyArguments::kMaxCases,
                                static_cast<double>(max_cases));
  const studies::StudySpec study =
      text ? studies::ParseStudy(*text, path, std::filesystem::path(path).parent_path().string())
           : studies::ReadStudy(path);
  CancelToken token;
  const Progress report(std::move(progress), &token);
  // The library's run: the record the program writes, and every row for the columns below.
  class Rows final : public studies::StudySink {
   public:
    explicit Rows(const Progress& report) : report_(report) {}
    void Row(const studies::CaseRow&, long rows, long total) override { report_(rows, total); }

   private:
    const Progress& report_;
  };
  const studies::StudyRun outcome = RunReleased(token, [&] {
    TemporaryRows temporary;
    studies::StudyRequest request;
    request.study = study;
    request.study_path = path;
    request.rows_file = rows_file ? *rows_file : temporary.path();
    request.cache_directory = cache_dir ? *cache_dir : transmission::DefaultCacheDirectory();
    request.threads = threads;
    request.max_cases = max_cases;
    Rows sink(report);
    return studies::RunStudy(request, sink);
  });
  const studies::RunReport& run = outcome.report;
  const std::vector<std::string> columns = study.Columns();
  const auto count = static_cast<py::ssize_t>(run.rows.size());
  const auto width = static_cast<py::ssize_t>(columns.size());
  std::vector<long> id;
  std::vector<double> values, kg, kgm, lmin, lmax, te, orbit, helical;
  const std::vector<std::string> helical_columns = study.HelicalColumns();
  std::vector<int> positions, converged;
  std::vector<char> ok;
  py::list message, lines, status;
  for (const studies::CaseRow& r : run.rows) {
    id.push_back(r.id);
    values.insert(values.end(), r.values.begin(), r.values.end());
    ok.push_back(r.ok());
    status.append(transmission::RunStatusName(r.status));
    message.append(r.message);
    positions.push_back(r.positions);
    converged.push_back(r.converged);
    kg.push_back(r.k_gamma);
    kgm.push_back(r.k_gamma_mean);
    lmin.push_back(r.lsr_min);
    lmax.push_back(r.lsr_max);
    te.push_back(r.te_peak_to_peak);
    orbit.push_back(r.sun_orbit);
    for (std::size_t c = 0; c < helical_columns.size(); ++c)
      helical.push_back(r.ok() && c < r.helical.size() ? r.helical[c] : kNaN);
    lines.append(r.Format());
  }
  const studies::StudySummary& sum = outcome.record->summary;
  py::dict summary;
  summary["cases"] = sum.cases;
  summary["failed"] = sum.failed;
  summary["k_gamma"] = SampleObject(sum.k_gamma);
  summary["k_gamma_mean"] = SampleObject(sum.k_gamma_mean);
  summary["te_peak_to_peak_urad"] = SampleObject(sum.te_peak_to_peak);
  summary["sun_orbit_um"] = SampleObject(sum.sun_orbit);
  summary["spearman_k_gamma"] = Array(std::vector<double>(sum.spearman));
  py::list exceedance;  // P(K_γ > each k_gamma_limit), Clopper–Pearson
  for (const studies::Exceedance& e : sum.k_gamma_exceedance) {
    exceedance.append(Result(py::dict(
        py::arg("k_gamma_limit") = e.threshold, py::arg("cases") = e.count,
        py::arg("above") = e.above, py::arg("probability") = e.p, py::arg("lower") = e.lower,
        py::arg("upper") = e.upper, py::arg("confidence_level") = e.level)));
  }
  summary["k_gamma_exceedance"] = exceedance;
  if (sum.sobol) {
    const studies::SobolSummary& sobol = *sum.sobol;
    py::dict outputs;
    for (const studies::SobolOutput& o : sobol.outputs)
      outputs[o.name.c_str()] = SobolObject(o.estimate);
    py::dict d;
    d["variables"] = sobol.variables;
    d["complete_rows"] = sobol.complete_rows;
    d["outputs"] = Result(outputs);
    summary["sobol"] = Result(d);
  }
  py::dict f;
  f["study"] = study.name;
  f["cases"] = study.Cases();
  f["columns"] = columns;
  f["case_id"] = Array(std::move(id));
  f["values"] = Array2(std::move(values), count, width);
  f["ok"] = BoolArray(ok);
  f["status"] = status;
  f["message"] = message;
  f["positions"] = Array(std::move(positions));
  f["converged"] = Array(std::move(converged));
  f["k_gamma"] = Array(std::move(kg));
  f["k_gamma_mean"] = Array(std::move(kgm));
  f["lsr_min"] = Array(std::move(lmin));
  f["lsr_max"] = Array(std::move(lmax));
  f["te_peak_to_peak_urad"] = Array(std::move(te));
  f["sun_orbit_um"] = Array(std::move(orbit));
  if (!helical_columns.empty()) {  // a helical stage's axial loads (StudySpec::HelicalColumns)
    f["helical_columns"] = helical_columns;
    f["helical"] = Array2(std::move(helical), count,
                          static_cast<py::ssize_t>(helical_columns.size()));
  }
  f["header"] = studies::RowHeader(study);
  f["rows_csv"] = lines;
  f["resumed"] = run.resumed;
  f["computed"] = run.computed;
  f["seconds"] = run.seconds;
  f["summary"] = Result(summary);
  f["warnings"] = study.warnings;
  // The program's summary JSON (`epicycle study`), its one serialisation, without provenance.
  f["record"] = JsonToPython(report::RecordJson(*outcome.record));
  py::object result = Result(f);
  // As the program exits 1 (docs/studies.md, "Results"): the cases that failed, by status.
  if (raise_on_failure)
    RaiseFailedParts(run.rows, "cases", "(result.status and result.message say why)", result);
  return result;
}

// One shard's part (`epicycle study FILE --cases I:J | --shard K/N --out DIR`): the same file
// and bytes as the program writes for the same study path.
py::object StudyPart(const std::string& path, std::optional<std::pair<long, long>> cases,
                     std::optional<std::pair<long, long>> shard, const std::string& out_dir,
                     int threads, std::optional<std::string> cache_dir, py::object progress) {
  transmission::CheckArgument("threads", threads, transmission::kThreadsOrZero);
  studies::StudySpec study = studies::ReadStudy(path);
  if (cases.has_value() == shard.has_value())
    throw std::invalid_argument(
        "cases and shard: give exactly one (cases=(I, J): the ids I <= k < J; shard=(K, N): "
        "shard K of N, K from 0)");
  const studies::CaseRange range =
      cases ? studies::CaseRange{cases->first, cases->second}
            : studies::ShardRange(study.Cases(), shard->first, shard->second, "shard");
  studies::CheckCaseRange(range, study.Cases(), "cases");
  CancelToken token;
  const Progress report(std::move(progress), &token);
  studies::RunOptions o;
  o.part = range;
  std::filesystem::create_directories(out_dir);
  o.rows_file = (std::filesystem::path(out_dir) / studies::PartFileName(range)).string();
  o.comment = report::StudyComment(report::Provenance(study.backend_name, &study.scene), path);
  o.cache_directory = cache_dir ? *cache_dir : transmission::DefaultCacheDirectory();
  o.threads =
      threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.on_row = [&](const studies::CaseRow&, long rows, long total) { report(rows, total); };
  const studies::RunReport run = RunReleased(token, [&] { return studies::RunStudy(study, o); });
  long failed = 0;
  for (const studies::CaseRow& r : run.rows) failed += r.ok() ? 0 : 1;
  py::dict f;
  f["part_file"] = o.rows_file;
  f["first_case"] = range.first;
  f["last_case"] = range.last;
  f["cases"] = study.Cases();
  f["rows"] = static_cast<long>(run.rows.size());
  f["failed"] = failed;
  f["resumed"] = run.resumed;
  f["computed"] = run.computed;
  f["seconds"] = run.seconds;
  return Result(f);
}

py::object StudyMerge(const std::vector<std::string>& parts, const std::string& out_dir,
                      std::optional<std::string> study) {
  const report::MergedStudy m = report::MergeStudy(parts, out_dir, study.value_or(""));
  const std::filesystem::path base = std::filesystem::path(out_dir) / "study";
  py::dict f;
  f["study"] = m.study.name;
  f["study_file"] = m.study_path;
  f["parts"] = m.parts;
  f["cases"] = m.study.Cases();
  f["failed"] = m.record.summary.failed;
  f["rows_file"] = base.string() + "_rows.csv";
  f["summary_file"] = base.string() + "_summary.json";
  f["k_gamma"] = SampleObject(m.record.summary.k_gamma);
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

py::object SobolObject(const studies::SobolEstimate& e) {
  py::dict f;
  f["rows"] = e.rows;
  f["mean"] = e.mean;
  f["variance"] = e.variance;
  for (const char* kind : {"first", "total"}) {
    const auto& x = std::string(kind) == "first" ? e.first : e.total;
    std::vector<double> value, lower, upper, se;
    for (const studies::SobolIndex& i : x) {
      value.push_back(i.value);
      lower.push_back(i.lower);
      upper.push_back(i.upper);
      se.push_back(i.standard_error);
    }
    const std::string k(kind);
    f[(k).c_str()] = Array(std::move(value));
    f[(k + "_lower").c_str()] = Array(std::move(lower));
    f[(k + "_upper").c_str()] = Array(std::move(upper));
    f[(k + "_standard_error").c_str()] = Array(std::move(se));
  }
  f["sum_first"] = e.sum_first.value;
  f["sum_first_lower"] = e.sum_first.lower;
  f["sum_first_upper"] = e.sum_first.upper;
  return Result(f);
}

}  // namespace

void BindStudies(py::module_& m) {
  m.def(
      "sobol_indices",
      [](const std::vector<double>& y, int d, int bootstrap, double level, std::uint64_t seed) {
        studies::SobolOptions o;
        o.bootstrap = bootstrap;
        o.level = level;
        o.seed = seed;
        return SobolObject(studies::EstimateSobol(y, d, o));
      },
      py::arg("y"), py::arg("d"), py::kw_only(), py::arg("bootstrap") = 1000,
      py::arg("level") = 0.95, py::arg("seed") = 0, R"doc(
First-order and total Sobol indices of one output (studies::EstimateSobol; docs/studies.md
"Sensitivity: Sobol indices"): first order Saltelli 2010, total Jansen, outputs centred on their
mean, V(Y) from A and B; rows with a non-finite value left out.

Parameters
----------
y : list of float
    The output's values in the Saltelli design's order y[j (d + 2) + m]: m = 0 row j of A, 1 of
    B, 2 + i of A_B^(i) (A with variable i from B); any unit.
d : int
    Variables [-].
bootstrap : int, default 1000
    Resamples of the rows for the percentile intervals [-] (0: none).
level : float, default 0.95
    Confidence level of the intervals [-].
seed : int, default 0
    Seed of the resampling.

Returns
-------
Result
    rows [-], mean and variance (y's unit and its square), first, first_lower, first_upper,
    first_standard_error, total, total_lower, total_upper, total_standard_error (arrays of d)
    [-], sum_first (Σ S_i), sum_first_lower, sum_first_upper [-].

Raises
------
ValueError
    A length of y that is not a multiple of d + 2, a bad d, bootstrap or level.)doc");

  m.def(
      "study",
      [](const std::string& path, std::optional<std::string> text, int threads, long max_cases,
         std::optional<std::string> rows_file, std::optional<std::string> cache_dir,
         py::object progress, bool raise_on_failure) {
        return Study(path, text, threads, max_cases, rows_file, cache_dir, std::move(progress),
                     raise_on_failure);
      },
      py::arg("path"), py::kw_only(), py::arg("text") = py::none(),
      py::arg("threads") = studies::StudyRequest().threads,
      py::arg("max_cases") = studies::StudyRequest().max_cases, py::arg("rows_file") = py::none(),
      py::arg("cache_dir") = py::none(), py::arg("progress") = py::none(),
      py::arg("raise_on_failure") = true, R"doc(
A tolerance study (`epicycle study`; docs/studies.md): every case a quasi-static sweep of the base
scene with its sampled errors, on threads.

Parameters
----------
path : str
    The study file (TOML).
text : str or None, default None
    The study's text instead (path then names it in messages and its folder resolves the scene
    path).
threads : int, default 0
    Workers [-] (0: every core).
max_cases : int, default -1
    Stop after this many new cases [-] (< 0: all).
rows_file : str or None, default None
    A rows CSV to write and resume (None: a temporary one, removed).
cache_dir : str or None, default None
    Influence-table cache (as quasistatic's).
progress : callable or None, default None
    progress(rows, total), called as cases complete.
raise_on_failure : bool, default True
    Raise when a case failed (else return the Result), as the program exits 1.

Returns
-------
Result
    Per case (sorted by case_id): case_id, values (cases, columns) [the columns' units: _um µm,
    _deg deg, _Nm N·m], ok, message, positions, converged, k_gamma [-], k_gamma_mean [-], lsr_min,
    lsr_max [-], te_peak_to_peak_urad [µrad], sun_orbit_um [µm]; a helical stage's
    helical_columns (the rows file's axial-load columns, their units in their names: F_a_<mesh>_N
    [N], M_tilt_*_Nm [N·m], with pins tilt_*_urad [µrad]) and helical (cases, helical_columns),
    the case's means over its positions (NaN where failed); columns, header and rows_csv
    (each row as the rows file has it); summary (cases, failed, k_gamma, k_gamma_mean,
    te_peak_to_peak_urad, sun_orbit_um: count, mean, percentiles with confidence intervals;
    spearman_k_gamma per column; k_gamma_exceedance, per k_gamma_limit of the study its
    k_gamma_limit, cases, above, probability P(K_gamma > limit) and its Clopper-Pearson lower and
    upper bounds, confidence_level; with design = "sobol" also sobol: variables, complete_rows and
    outputs, per rows-file result column the sobol_indices Result); study, cases, resumed,
    computed, seconds [s], warnings; record: the study's record, the keys and values of
    `epicycle study`'s study_summary.json (docs/records.md).

Raises
------
ValueError
    A bad study file or argument (its name, value and rule).
ComputationError
    A case failed and raise_on_failure: the subclass of the failed cases' status when they share
    one (ContactFailure, GeometryFailure, BadSampledValue), its .result the Result above.)doc");
  m.def("study_part", &StudyPart, py::arg("path"), py::kw_only(), py::arg("cases") = py::none(),
        py::arg("shard") = py::none(), py::arg("out_dir"), py::arg("threads") = 1,
        py::arg("cache_dir") = py::none(), py::arg("progress") = py::none(), R"doc(
One shard of a study (`epicycle study PATH --cases I:J | --shard K/N --out OUT_DIR`; docs/studies.md
"Shards"), with the seeds of a whole run, into OUT_DIR/study_cases_I_J.csv (resumed if it exists:
a killed shard run again computes only its missing cases).

Parameters
----------
path : str
    The study file (TOML).
cases : tuple of int or None, default None
    (I, J): the cases I <= k < J [-].
shard : tuple of int or None, default None
    (K, N): shard K of N, K from 0 [-] (give cases or shard).
out_dir : str
    The folder of the part file.
threads : int, default 1
    Workers [-] (1: a scheduler runs one shard per core; 0: every core).
cache_dir : str or None, default None
    Influence-table cache (as quasistatic's).
progress : callable or None, default None
    progress(rows, total), called as cases complete.

Returns
-------
Result
    part_file, first_case, last_case, cases (the study's), rows, failed, resumed, computed,
    seconds [s].

Raises
------
ValueError
    A bad study file, case range or shard (its name, value and rule).)doc");
  m.def("study_merge", &StudyMerge, py::arg("parts"), py::kw_only(), py::arg("out_dir"),
        py::arg("study") = py::none(), R"doc(
Joins a study's parts (`epicycle study merge PARTS --out OUT_DIR`) into the files a single run
writes: OUT_DIR/study_rows.csv, _summary.json, _kgamma_hist.svg, _kgamma_cdf.svg (and _sobol.svg
for a Sobol design).

Parameters
----------
parts : list of str
    Part files or folders of them.
out_dir : str
    The folder of the merged files.
study : str or None, default None
    The study file (None: the one the first part names).

Returns
-------
Result
    study, study_file, parts, cases, failed, rows_file, summary_file, k_gamma.

Raises
------
ValueError
    A part of another study, two parts sharing cases (a shard given twice) or cases in no part (a
    missing shard), naming the part files and the case range.)doc");
}

}  // namespace epicycle::python
