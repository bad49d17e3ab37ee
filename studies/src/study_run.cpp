// One tolerance study as a request, a run and a record (study_run.hpp; docs/studies.md).
#include "epicycle/studies/study_run.hpp"

#include <algorithm>
#include <thread>
#include <vector>

namespace epicycle::studies {

namespace {

using transmission::RecordVisitor;

// A list of objects, one per item (`fields` visits an item's), left out when empty.
template <typename T, typename Fields>
void VisitItems(RecordVisitor& visit, const char* key, const std::vector<T>& items,
                const Fields& fields) {
  if (items.empty()) return;
  visit.BeginList(key);
  for (const T& item : items) {
    visit.Item();
    fields(item);
  }
  visit.EndList();
}

// A sample's statistics: count, mean with its interval, spread, extremes and percentiles with
// theirs (docs/studies.md "Statistics").
void VisitSample(const char* key, const SampleSummary& s, RecordVisitor& visit) {
  visit.BeginObject(key);
  visit.Integer("count", s.count);
  visit.Number("mean", s.mean);
  visit.Numbers("mean_ci", {s.mean_lower, s.mean_upper});
  visit.Number("std", s.standard_deviation);
  visit.Number("min", s.min);
  visit.Number("max", s.max);
  visit.Number("confidence_level", s.level);
  visit.BeginList("percentiles");
  for (const Percentile& q : s.percentiles) {
    visit.Item();
    visit.Number("p", q.p);
    visit.Number("value", q.value);
    visit.Numbers("ci", {q.lower, q.upper});
  }
  visit.EndList();
  visit.EndObject();
}

void VisitIndex(const SobolIndex& x, RecordVisitor& visit) {
  visit.Number("value", x.value);
  visit.Numbers("ci", {x.lower, x.upper});
  visit.Number("standard_error", x.standard_error);
}

void VisitIndices(const char* key, const std::vector<std::string>& variables,
                  const std::vector<SobolIndex>& x, RecordVisitor& visit) {
  visit.BeginList(key);
  for (std::size_t i = 0; i < x.size(); ++i) {
    visit.Item();
    visit.Text("variable", variables[i]);
    VisitIndex(x[i], visit);
  }
  visit.EndList();
}

// The Sobol indices of every output (docs/studies.md "Sobol indices").
void VisitSobol(const SobolSummary& s, RecordVisitor& visit) {
  visit.BeginObject("sobol");
  visit.Text("design", "Saltelli: A, B and A_B^(i) of N rows each, N (d + 2) cases");
  visit.Text("estimators",
             "first order: Saltelli et al. 2010 (1/N) sum y_B (y_ABi - y_A) / V; total: Jansen "
             "(1/2N) sum (y_A - y_ABi)^2 / V; outputs centred on their mean, V from A and B");
  visit.Text("intervals", "percentile bootstrap over the rows j");
  visit.Integer("base_samples_N", s.base_samples);
  visit.Integer("complete_rows", s.complete_rows);
  visit.Integer("bootstrap_resamples", s.bootstrap);
  visit.Number("confidence_level", s.level);
  visit.Texts("variables", s.variables);
  visit.BeginObject("outputs");
  for (const SobolOutput& o : s.outputs) {
    const SobolEstimate& e = o.estimate;
    visit.BeginObject(o.name.c_str());
    visit.Integer("rows", e.rows);
    visit.Number("mean", e.mean);
    visit.Number("variance", e.variance);
    VisitIndices("first_order", s.variables, e.first, visit);
    VisitIndices("total", s.variables, e.total, visit);
    visit.BeginObject("sum_first_order");
    VisitIndex(e.sum_first, visit);
    visit.EndObject();
    visit.EndObject();
  }
  visit.EndObject();
  visit.EndObject();
}

}  // namespace

StudyRecord MakeStudyRecord(const StudySpec& study, const std::string& study_path,
                            const std::vector<CaseRow>& rows, double computed_seconds) {
  StudyRecord record;
  record.study = study_path;
  record.study_hash = study.hash;
  record.seed = study.seed;
  record.cases_total = study.Cases();
  record.summary = SummariseStudy(study, rows);
  record.warnings = study.warnings;
  record.computed_seconds = computed_seconds;
  return record;
}

StudyRun RunStudy(const StudyRequest& request, StudySink& sink) {
  StudySpec study = request.study;
  study.scene.model.stresses = study.scene.model.stresses || request.stresses;
  RunOptions opt;
  opt.part = request.part;
  opt.rows_file = request.rows_file;
  opt.comment = request.comment;
  opt.cache_directory = request.cache_directory;
  opt.threads = request.threads > 0
                    ? request.threads
                    : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  opt.max_new_cases = request.max_cases;
  opt.on_row = [&](const CaseRow& r, long rows, long total) { sink.Row(r, rows, total); };
  StudyRun run;
  run.report = RunStudyMpi(study, opt);
  if (request.rank == 0 && !request.part)
    run.record = MakeStudyRecord(study, request.study_path, run.report.rows, run.report.seconds);
  return run;
}

void VisitRecord(const StudyRecord& r, RecordVisitor& visit) {
  const StudySummary& s = r.summary;
  visit.Text("study", r.study);
  visit.Text("study_hash", r.study_hash);
  visit.Unsigned("seed", r.seed);
  visit.Integer("cases_total", r.cases_total);
  visit.Integer("cases_in_file", s.cases);
  visit.Integer("cases_failed", s.failed);
  visit.BeginObject("cases_failed_by_status");
  visit.Integer(transmission::RunStatusName(transmission::RunStatus::kContactFailure),
                s.failed_contact);
  visit.Integer(transmission::RunStatusName(transmission::RunStatus::kGeometry), s.failed_geometry);
  visit.Integer(transmission::RunStatusName(transmission::RunStatus::kBadSampledValue),
                s.failed_bad_sampled_value);
  visit.EndObject();
  visit.Text("statistics_note",
             "mean CI: normal approximation x +- z s/sqrt(n); percentile CIs: exact binomial order "
             "statistics (distribution-free), null where n is too small for the bound");
  VisitSample("K_gamma", s.k_gamma, visit);
  VisitSample("K_gamma_sweep_mean", s.k_gamma_mean, visit);
  VisitSample("TE_peak_to_peak_urad", s.te_peak_to_peak, visit);
  VisitSample("sun_orbit_um", s.sun_orbit, visit);
  if (!s.k_gamma_exceedance.empty()) {
    visit.BeginList("K_gamma_exceedance");
    for (const Exceedance& e : s.k_gamma_exceedance) {
      visit.Item();
      visit.Number("k_gamma_limit", e.threshold);
      visit.Integer("cases", e.count);
      visit.Integer("above", e.above);
      visit.Number("probability", e.p);
      visit.Numbers("ci", {e.lower, e.upper});
      visit.Text("interval", "Clopper-Pearson (exact binomial)");
      visit.Number("confidence_level", e.level);
    }
    visit.EndList();
  }
  VisitItems(visit, "root_stress", s.root_stress, [&](const GearStressStatistics& g) {
    visit.Text("gear", g.gear);
    VisitSample("tension_MPa", g.tension, visit);
    VisitSample("compression_magnitude_MPa", g.compression, visit);
    VisitSample("largest_range_MPa", g.range, visit);
    if (g.s_f.count > 0) VisitSample("S_F", g.s_f, visit);
    if (g.s_h.count > 0) VisitSample("S_H", g.s_h, visit);
  });
  VisitItems(visit, "face_width", s.face_width, [&](const MeshFaceStatistics& m) {
    visit.Text("mesh", m.mesh);
    VisitSample("K_Hbeta_max", m.k_h_beta, visit);
    VisitSample("K_gamma_K_Hbeta_max", m.k_gamma_k_h_beta, visit);
  });
  if (!s.helical.empty()) {
    // A helical stage's axial loads, each column's values over the cases (runner.hpp).
    visit.BeginObject("helical");
    for (const ColumnStatistics& c : s.helical) VisitSample(c.column.c_str(), c.values, visit);
    visit.EndObject();
  }
  visit.BeginObject("spearman_K_gamma");  // ρ_s per sampled-value column (null: constant)
  for (std::size_t k = 0; k < s.columns.size(); ++k)
    visit.Number(s.columns[k].c_str(), s.spearman[k]);
  visit.EndObject();
  if (s.sobol) VisitSobol(*s.sobol, visit);
  visit.Texts("warnings", r.warnings);
  visit.Number("computed_seconds", r.computed_seconds);
}

}  // namespace epicycle::studies
