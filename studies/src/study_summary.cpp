#include "epicycle/studies/study_summary.hpp"

#include <algorithm>
#include <cmath>

#include "epicycle/studies/sobol.hpp"

namespace epicycle::studies {

StudySummary SummariseStudy(const StudySpec& study, const std::vector<CaseRow>& all_rows,
                            double level) {
  StudySummary s;
  s.cases = static_cast<long>(all_rows.size());
  for (const CaseRow& r : all_rows) {
    s.failed += r.ok() ? 0 : 1;
    s.failed_contact += r.status == transmission::RunStatus::kContactFailure ? 1 : 0;
    s.failed_geometry += r.status == transmission::RunStatus::kGeometry ? 1 : 0;
    s.failed_bad_sampled_value += r.status == transmission::RunStatus::kBadSampledValue ? 1 : 0;
  }
  // The distributions need independent cases: of a Sobol design, those of A and B (the
  // A_B^(i) repeat all but one of A's values).
  std::vector<CaseRow> independent;
  if (study.design == Design::kSobol)
    for (const CaseRow& r : all_rows)
      if (SobolCaseOf(study, r.id).matrix <= 1) independent.push_back(r);
  const std::vector<CaseRow>& rows = study.design == Design::kSobol ? independent : all_rows;
  s.columns = study.Columns();
  std::vector<double> kg, kgm, te, orbit;
  std::vector<std::vector<double>> values(s.columns.size());
  for (const CaseRow& r : rows) {
    if (!r.ok()) continue;
    kg.push_back(r.k_gamma);
    kgm.push_back(r.k_gamma_mean);
    te.push_back(r.te_peak_to_peak);
    orbit.push_back(r.sun_orbit);
    for (std::size_t j = 0; j < values.size(); ++j) values[j].push_back(r.values.at(j));
  }
  s.k_gamma = Summarise(kg, kStudyPercentiles, level);
  s.k_gamma_mean = Summarise(kgm, kStudyPercentiles, level);
  s.te_peak_to_peak = Summarise(te, kStudyPercentiles, level);
  s.sun_orbit = Summarise(orbit, kStudyPercentiles, level);
  for (const auto& v : values) s.spearman.push_back(SpearmanCorrelation(v, kg));
  for (double x : study.k_gamma_limits)
    s.k_gamma_exceedance.push_back(ExceedanceProbability(kg, x, level));
  s.k_gamma_histogram = MakeHistogram(kg);
  s.k_gamma_sorted = kg;
  std::sort(s.k_gamma_sorted.begin(), s.k_gamma_sorted.end());
  const std::vector<std::string> gears = study.StressGears();
  for (std::size_t g = 0; g < gears.size(); ++g) {
    std::vector<double> tension, compression, range, s_f, s_h;
    for (const CaseRow& r : rows) {
      if (!r.ok() || r.root_stress.size() != 3 * gears.size()) continue;
      tension.push_back(r.root_stress[3 * g]);
      compression.push_back(std::abs(r.root_stress[3 * g + 1]));
      range.push_back(r.root_stress[3 * g + 2]);
      if (r.safety.size() != 2 * gears.size()) continue;
      s_f.push_back(r.safety[2 * g]);  // NaN (no tension or pressure in the case): skipped
      s_h.push_back(r.safety[2 * g + 1]);
    }
    s.root_stress.push_back({gears[g], Summarise(tension, kStudyPercentiles, level),
                             Summarise(compression, kStudyPercentiles, level),
                             Summarise(range, kStudyPercentiles, level),
                             Summarise(s_f, kSafetyPercentiles, level),
                             Summarise(s_h, kSafetyPercentiles, level)});
  }
  const std::vector<std::string> meshes = study.FaceMeshes();
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    std::vector<double> k_h_beta, product;
    for (const CaseRow& r : rows) {
      if (!r.ok() || r.face_load.size() != 2 * meshes.size()) continue;
      k_h_beta.push_back(r.face_load[2 * m]);
      product.push_back(r.face_load[2 * m + 1]);
    }
    s.face_width.push_back({meshes[m], Summarise(k_h_beta, kStudyPercentiles, level),
                            Summarise(product, kStudyPercentiles, level)});
  }
  const std::vector<std::string> helical = study.HelicalColumns();
  for (std::size_t c = 0; c < helical.size(); ++c) {
    std::vector<double> v;
    for (const CaseRow& r : rows)
      if (r.ok() && r.helical.size() == helical.size()) v.push_back(r.helical[c]);
    s.helical.push_back({helical[c], Summarise(v, kStudyPercentiles, level)});
  }
  if (study.design == Design::kSobol) {
    SobolOptions so;
    so.seed = study.seed;
    so.level = level;
    s.sobol = SummariseSobol(study, all_rows, so);
  }
  return s;
}

}  // namespace epicycle::studies
