#include "epicycle/studies/runner.hpp"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "epicycle/io/enum_names.hpp"
#include "epicycle/io/input_file.hpp"
#include "epicycle/studies/sampling.hpp"
#include "epicycle/transmission/helical_scene.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/rating.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/scene.hpp"
#include "epicycle/transmission/sweep_summary.hpp"
#include "epicycle/transmission/validity.hpp"
#include "epicycle/transmission/work_queue.hpp"
#include "runner_internal.hpp"

namespace epicycle::studies {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kResultFields = 10;  // ok .. message, after the sampled values (then the check)

// The shortest text that reads back to the same double (std::to_chars): the same result always
// gives the same bytes, whatever thread or rank computed it. Non-finite: an empty field.
std::string Exact(double v) {
  if (!std::isfinite(v)) return "";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::vector<std::string> Split(const std::string& line) {
  std::vector<std::string> f;
  std::size_t start = 0;
  for (;;) {
    const std::size_t p = line.find(',', start);
    f.push_back(line.substr(start, p == std::string::npos ? std::string::npos : p - start));
    if (p == std::string::npos) return f;
    start = p + 1;
  }
}

bool ParseReal(const std::string& s, double* v) {
  if (s.empty()) {
    *v = kNaN;
    return true;
  }
  const auto r = std::from_chars(s.data(), s.data() + s.size(), *v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

bool ParseLong(const std::string& s, long* v) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), *v);
  return !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
}

std::string Clean(std::string m) {
  for (char& c : m)
    if (c == ',' || c == '\n' || c == '\r') c = ';';
  return m;
}

// The row's check field: the FNV-1a (64 bit) hash of every byte before ",<check>" as 16 hex
// digits (transmission::ContentHash without its "fnv1a64:" prefix). It tells a row as written from
// one changed afterwards (an edited value would otherwise be resumed and move the summary); it is
// a check of integrity against accidents, not a signature.
std::string RowCheck(std::string_view text) {
  return transmission::ContentHash(std::string(text)).substr(sizeof("fnv1a64:") - 1);
}

}  // namespace

std::string CaseRow::Format() const {
  // Appended piece by piece (GCC 12's -Wrestrict misfires on chained string additions).
  std::string s = std::to_string(id);
  auto field = [&s](const std::string& f) {
    s.push_back(',');
    s.append(f);
  };
  for (double v : values) field(Exact(v));
  field(ok() ? "ok" : transmission::RunStatusName(status));
  field(std::to_string(positions));
  field(std::to_string(converged));
  for (double v : {k_gamma, k_gamma_mean, lsr_min, lsr_max, te_peak_to_peak, sun_orbit})
    field(ok() ? Exact(v) : std::string());
  for (double v : root_stress) field(ok() ? Exact(v) : std::string());
  for (double v : safety) field(ok() ? Exact(v) : std::string());
  for (double v : face_load) field(ok() ? Exact(v) : std::string());
  for (double v : helical) field(ok() ? Exact(v) : std::string());
  field(Clean(message));
  field(RowCheck(s));
  s.push_back('\n');
  return s;
}

std::string RowHeader(const StudySpec& study) {
  std::string h = "case";
  for (const std::string& c : study.Columns()) {
    h.push_back(',');
    h.append(c);
  }
  h += ",status,positions,converged,K_gamma,K_gamma_mean,LSR_min,LSR_max,TE_pp_urad,sun_orbit_um";
  for (const std::string& g : study.StressGears())
    h += ",sigma_t_" + g + "_MPa,sigma_c_" + g + "_MPa,sigma_range_" + g + "_MPa";
  if (study.Rated())
    for (const std::string& g : study.StressGears()) h += ",S_F_" + g + ",S_H_" + g;
  for (const std::string& m : study.FaceMeshes()) h += ",K_Hbeta_" + m + ",K_gamma_K_Hbeta_" + m;
  for (const std::string& c : study.HelicalColumns()) h += "," + c;
  h += ",message,check";
  return h;
}

namespace internal {

std::string StudyLine(const StudySpec& study) {
  std::ostringstream o;
  o << "# study " << Clean(study.name) << "; study_hash " << study.hash << "; seed " << study.seed
    << "; cases " << study.Cases();
  return o.str();
}

std::string PartLine(const StudySpec& study, const CaseRange& range) {
  return "# part cases " + std::to_string(range.first) + ":" + std::to_string(range.last) + " of " +
         std::to_string(study.Cases()) + "; scene_hash " + study.scene.hash + "; stresses " +
         (study.scene.model.stresses ? "on" : "off");
}

std::string PartStudyFileLine(const StudySpec& study) {
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(study.source, error);
  return "# part of study file " + Clean(error ? study.source : absolute.string());
}

std::vector<double> CaseAngles(const StudySpec& study, const geometry::Stage& stage) {
  const double span = transmission::CarrierSpan(
      stage, study.compute == CaseKind::kMeshCycle ? transmission::RunRange::kMeshCycle
                                                   : transmission::RunRange::kPlanetRevolution);
  return transmission::SweepAngles(study.start_angle, span, study.positions);
}

CaseRow ParseRow(const std::string& line, const StudySpec& study, const std::string& where) {
  const std::vector<std::string> f = Split(line);
  const std::size_t nv = study.Columns().size();
  const std::size_t ns = 3 * study.StressGears().size();                      // root-stress fields
  const std::size_t nr = study.Rated() ? 2 * study.StressGears().size() : 0;  // safety factors
  const std::size_t nf = 2 * study.FaceMeshes().size();                       // face-load factors
  const std::size_t nh = study.HelicalColumns().size();                       // axial loads
  auto bad = [&](const std::string& why) {
    throw std::invalid_argument(where + ": not a row of this study (" + why + "): '" + line + "'");
  };
  if (f.size() != 1 + nv + kResultFields + ns + nr + nf + nh + 1)
    bad(std::to_string(f.size()) + " fields, " +
        std::to_string(1 + nv + kResultFields + ns + nr + nf + nh + 1) + " expected");
  // Changed after it was written: the check covers every byte before its own field.
  const std::string_view body(line.data(), line.size() - f.back().size() - 1);
  if (f.back() != RowCheck(body))
    throw std::invalid_argument(where +
                                ": the row was changed after it was written (its check field is '" +
                                f.back() + "', its text gives '" + RowCheck(body) +
                                "'): delete the line to compute the case again, or restore it");
  CaseRow r;
  if (!ParseLong(f[0], &r.id) || r.id < 0 || r.id >= study.Cases()) bad("case id");
  r.values.resize(nv);
  for (std::size_t j = 0; j < nv; ++j)
    if (!ParseReal(f[1 + j], &r.values[j])) bad("value " + study.Columns()[j]);
  // The sampled values are a function of (seed, case): a row whose values differ was not
  // computed by this study's sampling (written exactly, so they compare exactly).
  const std::vector<double> sampled = SampleCase(study, r.id);
  for (std::size_t j = 0; j < nv; ++j)
    if (!(r.values[j] == sampled[j]))
      throw std::invalid_argument(
          where + ": case " + std::to_string(r.id) + "'s " + study.Columns()[j] + " is " +
          f[1 + j] + ", but this study samples " + Exact(sampled[j]) + " for it (seed " +
          std::to_string(study.seed) + "): the row was not computed by this study");
  std::size_t k = 1 + nv;
  const std::optional<transmission::RunStatus> status =
      f[k] == "ok" ? transmission::RunStatus::kCompleted
                   : io::ValueOf(transmission::kRunStatusNames, f[k]);
  if (!status || (*status == transmission::RunStatus::kCompleted && f[k] != "ok")) bad("status");
  r.status = *status;
  ++k;
  long pos = 0, conv = 0;
  if (!ParseLong(f[k++], &pos) || !ParseLong(f[k++], &conv)) bad("position counts");
  r.positions = static_cast<int>(pos);
  r.converged = static_cast<int>(conv);
  for (double* v :
       {&r.k_gamma, &r.k_gamma_mean, &r.lsr_min, &r.lsr_max, &r.te_peak_to_peak, &r.sun_orbit})
    if (!ParseReal(f[k++], v)) bad("result value");
  r.root_stress.resize(ns);
  for (double& v : r.root_stress)
    if (!ParseReal(f[k++], &v)) bad("root stress");
  r.safety.resize(nr);
  for (double& v : r.safety)
    if (!ParseReal(f[k++], &v)) bad("safety factor");
  r.face_load.resize(nf);
  for (double& v : r.face_load)
    if (!ParseReal(f[k++], &v)) bad("face-load factor");
  r.helical.resize(nh);
  for (double& v : r.helical)
    if (!ParseReal(f[k++], &v)) bad("axial load");
  r.message = f[k];
  return r;
}

std::vector<long> MissingCases(const StudySpec& study, const std::vector<CaseRow>& rows, long limit,
                               const std::optional<CaseRange>& part) {
  std::vector<long> have;
  have.reserve(rows.size());
  for (const CaseRow& r : rows) have.push_back(r.id);
  std::sort(have.begin(), have.end());
  std::vector<long> missing;
  auto next = have.begin();
  const CaseRange range = part.value_or(CaseRange{0, study.Cases()});
  for (long k = range.first; k < range.last; ++k) {
    if (limit >= 0 && static_cast<long>(missing.size()) >= limit) break;
    while (next != have.end() && *next < k) ++next;
    if (next == have.end() || *next != k) missing.push_back(k);
  }
  return missing;
}

RowWriter::RowWriter(const std::string& path, const StudySpec& study, const std::string& comment,
                     bool exists, const std::optional<CaseRange>& part) {
  file_ = std::fopen(path.c_str(), "ab");
  if (file_ == nullptr) throw std::runtime_error(path + ": cannot write the study's rows");
  path_ = path;
  if (!exists) {
    std::string head;
    if (!comment.empty()) head += "# " + Clean(comment) + "\n";
    head += StudyLine(study) + "\n";
    if (part) head += PartLine(study, *part) + "\n" + PartStudyFileLine(study) + "\n";
    head += RowHeader(study) + "\n";
    Write(head);
  }
}

RowWriter::~RowWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void RowWriter::Write(const std::string& text) {
  // One fwrite of the whole line, then flushed to the kernel: a process killed now leaves the
  // line whole or a prefix without its '\n' (dropped by ReadRows), never a valid-looking half.
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0)
    throw std::runtime_error(path_ + ": cannot write the study's rows");
}

// Runs `ids` on `threads` workers, each with its own solver; `sink` gets every row (called under
// one lock, in completion order). Stops taking cases after `limit` (< 0: none).
void ComputeCases(const StudySpec& study, const transmission::StageCompliance& compliance,
                  const std::string& cache_directory, const std::vector<long>& ids, int threads,
                  long limit, bool warm_start, const std::function<void(const CaseRow&)>& sink) {
  CaseStarts starts(study, compliance, warm_start);
  const std::size_t count =
      limit < 0 ? ids.size() : std::min(ids.size(), static_cast<std::size_t>(limit));
  std::vector<CaseRow> rows(count);
  transmission::RunWorkQueue(
      count, threads,
      [&](std::size_t i) {
        rows[i] = ComputeCase(study, compliance, ids[i], cache_directory, starts.For(ids[i]));
      },
      [&](std::size_t i) {
        sink(rows[i]);
        rows[i] = CaseRow{};  // written: its memory goes
      });
}

std::unique_ptr<transmission::FeStageCompliance> NominalCompliance(
    const StudySpec& study, const std::string& cache_directory) {
  // The bodies of the base scene: the tables depend on the nominal bodies only (a thickness
  // error is a surface offset, compliance::NominalBody), so every case shares them.
  // A helical stage runs in slices at their own sections' poses (docs/model.md §10).
  transmission::RequireHelicalSlices(study.scene, "`epicycle study`");
  transmission::FeComplianceOptions fe;
  fe.cache_directory = cache_directory;
  fe.helical_slices = true;
  const geometry::Stage stage = transmission::MakeStage(study.scene);
  return std::make_unique<transmission::FeStageCompliance>(study.scene, stage, fe);
}

}  // namespace internal

namespace {

// A helical case's StudySpec::HelicalColumns from its sweep's means into `values` (sized to the
// columns; left NaN where the sweep has none).
void HelicalValues(const transmission::SweepSummary& s, int planets, std::vector<double>* values) {
  if (values->empty() || s.helical_mean.planets.size() != static_cast<std::size_t>(planets))
    return;
  std::size_t k = 0;
  std::vector<double>& v = *values;
  for (const transmission::PlanetHelicalLoad& p : s.helical_mean.planets) v[k++] = p.sun_mesh_axial;
  for (const transmission::PlanetHelicalLoad& p : s.helical_mean.planets) v[k++] = p.ring_mesh_axial;
  for (const transmission::PlanetHelicalLoad& p : s.helical_mean.planets) {
    v[k++] = p.moment_radial;
    v[k++] = p.moment_tangential;
  }
  if (k == v.size() || s.pin_tilts.size() != static_cast<std::size_t>(planets)) return;
  for (const transmission::SweepSummary::PinTiltSummary& t : s.pin_tilts) {
    v[k++] = t.radial_mean * 1e6;
    v[k++] = t.tangential_mean * 1e6;
  }
}

// A case's scene, stage, supports and carrier angles (its values applied to the base scene).
struct CaseRig {
  transmission::Scene scene;
  transmission::RatingInputs rating;  // what the case's rating takes (its own torque and leads)
  geometry::Stage stage;
  transmission::StageSetup setup;
  std::vector<double> angles;
  transmission::QuasiStaticOptions options;
  CaseRig(const StudySpec& study, const std::vector<double>& values)
      : scene(CaseScene(study, values)),
        rating(transmission::RatingInputsOf(scene)),
        stage(transmission::MakeStage(scene)),
        setup(transmission::SetupFromScene(scene)),
        angles(internal::CaseAngles(study, stage)) {
    if (study.sun) setup.sun = *study.sun;
    options.backend = study.backend;
    options.threads = 1;  // the cases already run on every core (ComputeCases): no nested workers
  }
};

}  // namespace

namespace internal {

CaseStarts::CaseStarts(const StudySpec& study, const transmission::StageCompliance& compliance,
                       bool enabled)
    : study_(study), compliance_(compliance) {
  // Tables of their own per case (a crack's depth): no shared start. Past kMaxGridPoints grid
  // points the starts' memory (each holds its contact problem) is not spent: cold.
  if (enabled && !study.VariesBodies() && study.GridPoints() <= kMaxGridPoints) {
    const auto points = static_cast<std::size_t>(study.GridPoints());
    once_ = std::make_unique<std::once_flag[]>(points);
    starts_.resize(points);
  }
}

const transmission::PositionResult* CaseStarts::For(long case_id) {
  if (starts_.empty()) return nullptr;
  // Case g (< GridPoints) is the first sample of grid point g = case_id mod G (sampling.hpp).
  const long g = case_id % study_.GridPoints();
  const auto i = static_cast<std::size_t>(g);
  std::call_once(once_[i], [&] {
    try {
      const CaseRig rig(study_, SampleCase(study_, g));
      transmission::SweepEach(
          transmission::StageModel(rig.stage, compliance_, rig.setup), rig.scene.loads, 1,
          [&](int) { return rig.angles.front(); }, rig.options,
          [&](const transmission::PositionResult& r, int) {
            if (r.converged) starts_[i] = std::make_unique<transmission::PositionResult>(r);
          });
    } catch (const std::exception&) {
      // A grid point whose first case the geometry rejects: its cases start cold (and say why).
    }
  });
  return starts_[i].get();
}

}  // namespace internal

CaseRow ComputeCase(const StudySpec& study, const transmission::StageCompliance& compliance,
                    long case_id, const std::string& cache_directory,
                    const transmission::PositionResult* start) {
  CaseRow row;
  row.id = case_id;
  row.values = SampleCase(study, case_id);
  const std::vector<std::string> gears = study.StressGears();
  row.root_stress.assign(3 * gears.size(), kNaN);
  row.safety.assign(study.Rated() ? 2 * gears.size() : 0, kNaN);
  const std::size_t meshes = study.FaceMeshes().size();
  row.face_load.assign(2 * meshes, kNaN);
  row.helical.assign(study.HelicalColumns().size(), kNaN);
  // The case's scene, stage and (for a crack's depth) own tables. The base scene passed every
  // rule when the study was read, so a rule broken here is a sampled value's.
  std::optional<CaseRig> built;
  std::unique_ptr<transmission::FeStageCompliance> own;
  try {
    built.emplace(study, row.values);
    // A case with its own bodies (a crack's depth) gets its own tables: the healthy ones read
    // from the cache, the cracked gear's damaged rows built (or read) for its crack.
    if (study.VariesBodies()) {
      transmission::FeComplianceOptions fe;
      fe.cache_directory = cache_directory;
      fe.helical_slices = true;  // the case's stage model resolves a helical stage in slices
      own = std::make_unique<transmission::FeStageCompliance>(built->scene, built->stage, fe);
    }
  } catch (const std::invalid_argument& e) {
    row.status = transmission::RunStatus::kBadSampledValue;
    row.message = e.what();
    return row;
  } catch (const std::exception& e) {
    row.status = transmission::RunStatus::kGeometry;
    row.message = e.what();
    return row;
  }
  try {
    const CaseRig& rig = *built;
    const transmission::Scene& scene = rig.scene;
    const geometry::Stage& stage = rig.stage;
    const std::vector<double>& angles = rig.angles;
    // The case needs the sweep's summary, its warnings and its first failure only.
    transmission::SweepAccumulator accumulator(stage.planets());
    transmission::ValidityTally tally(stage, "position(s)");
    std::string first_failure;
    transmission::SweepEach(
        transmission::StageModel(stage, own ? *own : compliance, rig.setup), scene.loads,
        static_cast<int>(angles.size()), [&](int k) { return angles[static_cast<std::size_t>(k)]; },
        rig.options,
        [&](const transmission::PositionResult& r, int) {
          accumulator.Add(r);
          tally.Add(r);
          if (!r.converged && first_failure.empty())
            first_failure =
                std::to_string(r.carrier_angle * 180.0 / std::numbers::pi) + " deg: " + r.message;
        },
        own ? nullptr : start);
    const transmission::SweepSummary s = accumulator.Result();
    row.positions = s.positions;
    row.converged = s.converged;
    row.status = s.converged == s.positions ? transmission::RunStatus::kCompleted
                                            : transmission::RunStatus::kContactFailure;
    if (row.ok()) {
      // Legal values outside the model's validity: the case stands, its message says so.
      for (const std::string& w : tally.Messages())
        row.message += (row.message.empty() ? "warning: " : " / warning: ") + w;
    } else {
      row.message = std::to_string(s.positions - s.converged) + " of " +
                    std::to_string(s.positions) + " positions failed; first at " + first_failure;
    }
    row.k_gamma = s.k_gamma;
    row.k_gamma_mean = s.k_gamma_mean;
    row.lsr_min = s.LsrMin();
    row.lsr_max = s.LsrMax();
    row.te_peak_to_peak = s.TransmissionErrorPeakToPeak() * 1e6;
    row.sun_orbit = s.sun_displacement_max * 1e6;
    // With stresses the shared tables have them, and every converged position carries its own.
    for (std::size_t g = 0; g < s.root_stress.size() && g < gears.size(); ++g) {
      row.root_stress[3 * g] = s.root_stress[g].extremes.tension / 1e6;
      row.root_stress[3 * g + 1] = s.root_stress[g].extremes.compression / 1e6;
      row.root_stress[3 * g + 2] = s.root_stress[g].range.range / 1e6;
    }
    // With slices of the face width, every converged position carries each mesh's face load.
    for (std::size_t m = 0; m < s.face_width.size() && m < meshes; ++m) {
      row.face_load[2 * m] = s.face_width[m].k_h_beta_max;
      row.face_load[2 * m + 1] = s.face_width[m].k_gamma_k_h_beta_max;
    }
    HelicalValues(s, stage.planets(), &row.helical);
    // The model's safety factors of every gear, from this case's own stresses (rating.hpp).
    if (study.Rated() && s.converged > 0) {
      const transmission::StageRating rating = transmission::RateStage(rig.rating, stage, s);
      for (std::size_t g = 0; g < gears.size(); ++g)
        for (const transmission::GearRating& r : rating.gears)
          if (r.gear == gears[g]) {
            row.safety[2 * g] = r.s_f_stress;
            row.safety[2 * g + 1] = r.s_h_pressure;
          }
    }
  } catch (const std::exception& e) {
    // The sweep could not evaluate the stage at these values (every position's own failure is
    // a row of its sweep, not an exception).
    row.status = transmission::RunStatus::kGeometry;
    row.message = e.what();
  }
  return row;
}

ExistingRows ReadRows(const std::string& path, const StudySpec& study,
                      const std::optional<CaseRange>& part) {
  ExistingRows out;
  std::error_code none;
  if (!std::filesystem::exists(path, none) && !std::filesystem::is_symlink(path, none)) return out;
  // As every input: a regular file (a symlink to a device is refused, not read forever).
  const std::string text =
      io::ReadInputFile(path, "study rows file (CSV)", std::numeric_limits<std::uintmax_t>::max());
  if (text.empty()) return out;
  // A last line without '\n' is a row (or header) the writer was killed in: cut it off.
  std::size_t complete = text.rfind('\n');
  complete = complete == std::string::npos ? 0 : complete + 1;
  if (complete < text.size()) {
    out.dropped_partial = true;
    std::filesystem::resize_file(path, complete);
  }
  std::istringstream lines(text.substr(0, complete));
  std::string line;
  int number = 0;
  bool study_line = false, header = false, part_line = false;
  std::set<long> seen;
  while (std::getline(lines, line)) {
    ++number;
    const std::string where = path + ":" + std::to_string(number);
    if (!line.empty() && line.back() == '\r')
      throw std::invalid_argument(
          where +
          ": the line ends in CR (carriage return): the file was converted to CRLF line "
          "ends after it was written; convert it back (dos2unix) to resume it");
    if (!header && line.rfind("# study ", 0) == 0) {
      if (line != internal::StudyLine(study))
        throw std::invalid_argument(where + ": the rows were written by another study ('" + line +
                                    "', this one is '" + internal::StudyLine(study) +
                                    "'): use another output folder or the same study file");
      study_line = true;
      continue;
    }
    if (!header && line.rfind("# part cases ", 0) == 0) {
      if (!part)
        throw std::invalid_argument(where + ": the file is a shard's part ('" + line +
                                    "'), not a whole study's rows: join the parts with `epicycle "
                                    "study merge` or run the same shard again to resume it");
      if (line != internal::PartLine(study, *part))
        throw std::invalid_argument(where +
                                    ": the part holds other cases or was written from "
                                    "another scene or with other outputs (--stresses) ('" +
                                    line + "', this shard's is '" +
                                    internal::PartLine(study, *part) +
                                    "'): use another output folder, or the shard's first options");
      part_line = true;
      continue;
    }
    if (!line.empty() && line[0] == '#') continue;
    if (!header) {
      if (part && study_line && !part_line)
        throw std::invalid_argument(where + ": the file holds a whole study's rows, not the part " +
                                    internal::PartLine(study, *part).substr(2) +
                                    ": use another output folder for the shards");
      if (!study_line || line != RowHeader(study))
        throw std::invalid_argument(where + ": not the rows file of this study (column line '" +
                                    line + "', this study's is '" + RowHeader(study) + "')");
      header = true;
      continue;
    }
    CaseRow r = internal::ParseRow(line, study, where);
    if (part && !part->Contains(r.id))
      throw std::invalid_argument(where + ": case " + std::to_string(r.id) +
                                  " is not one of the part's cases " + std::to_string(part->first) +
                                  ":" + std::to_string(part->last));
    if (!seen.insert(r.id).second)
      throw std::invalid_argument(where + ": case " + std::to_string(r.id) +
                                  " appears twice (two runs writing one file?)");
    out.rows.push_back(std::move(r));
  }
  if (!header) {
    // Killed before the column line was complete: nothing to keep, start the file anew.
    std::filesystem::resize_file(path, 0);
    return out;
  }
  out.exists = true;
  return out;
}

RunReport RunStudy(const StudySpec& study, const RunOptions& options) {
  RunReport report;
  ExistingRows existing = ReadRows(options.rows_file, study, options.part);
  report.resumed = static_cast<long>(existing.rows.size());
  report.dropped_partial = existing.dropped_partial;
  report.rows = std::move(existing.rows);
  const std::vector<long> missing =
      internal::MissingCases(study, report.rows, options.max_new_cases, options.part);
  internal::RowWriter writer(options.rows_file, study, options.comment, existing.exists,
                             options.part);
  if (!missing.empty() && options.max_new_cases != 0) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto compliance = internal::NominalCompliance(study, options.cache_directory);
    report.table_messages = compliance->tables().messages();
    const auto t1 = std::chrono::steady_clock::now();
    report.table_seconds = std::chrono::duration<double>(t1 - t0).count();
    internal::ComputeCases(study, *compliance, options.cache_directory, missing, options.threads,
                           options.max_new_cases, options.warm_start_cases,
                           [&](const CaseRow& row) {
                             writer.Write(row.Format());
                             report.rows.push_back(row);
                             ++report.computed;
                             if (options.on_row)
                               options.on_row(row, static_cast<long>(report.rows.size()),
                                              options.part ? options.part->Size() : study.Cases());
                           });
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  }
  std::sort(report.rows.begin(), report.rows.end(),
            [](const CaseRow& a, const CaseRow& b) { return a.id < b.id; });
  return report;
}

}  // namespace epicycle::studies
