// The fields of a driver's record, visited once each with the name (unit included) under which
// every serialisation writes them: report/ turns a visit into the summary JSON, the bindings into
// a dict, a test into the list of keys. A record defines its fields in one VisitRecord function,
// so that a new output is one field and one line there.
#pragma once

#include <string>
#include <vector>

namespace epicycle::solvers {
struct ComparisonRecord;
}

namespace epicycle::transmission {

struct SweepSummary;
struct StageRating;
struct RootStressSummary;

/// Receives a record's fields in order. Numbers are in the unit their key names ("_urad", "_Nm",
/// "_s"; none for a ratio); a number that is not finite means "none" (null in JSON, None in
/// Python).
class RecordVisitor {
 public:
  virtual ~RecordVisitor() = default;
  virtual void Number(const char* key, double value) = 0;
  virtual void Integer(const char* key, long value) = 0;
  /// A whole number that may exceed a long (a random seed).
  virtual void Unsigned(const char* key, unsigned long long value) = 0;
  virtual void Flag(const char* key, bool value) = 0;
  virtual void Text(const char* key, const std::string& value) = 0;
  virtual void Texts(const char* key, const std::vector<std::string>& value) = 0;
  /// A list of numbers in the key's unit (a pair of depths, a mode's speeds).
  virtual void Numbers(const char* key, const std::vector<double>& value) = 0;
  /// A list of whole numbers (a mode's cyclic-symmetry families).
  virtual void Integers(const char* key, const std::vector<long>& value) = 0;
  /// A record inside the record (the healthy teeth beside a damaged run): its fields follow,
  /// until EndObject().
  virtual void BeginObject(const char* key) = 0;
  virtual void EndObject() = 0;
  /// A list of objects with the same fields (the planets' statistics): Item() before each.
  virtual void BeginList(const char* key) = 0;
  virtual void Item() = 0;
  virtual void EndList() = 0;
  /// The fields of a sweep's root stresses and contact pressures and of a rating, as their
  /// serialisations define them (report::RootStressJson, ContactPressureJson, RatingJson).
  virtual void Stresses(const SweepSummary& summary) = 0;
  virtual void Rating(const char* key, const StageRating& rating) = 0;
  /// Each gear's root-stress extremes over a run (report::RootStressJson), where they occur as
  /// `x_key` = x · x_scale (a mesh-stiffness run's "angle_deg").
  virtual void RootStress(const char* key, const std::vector<RootStressSummary>& gears,
                          const char* x_key, double x_scale) = 0;
};

/// The planets' load-sharing ratios over a run as the list "planets": per planet its number (from
/// 1) and lsr_mean, lsr_min, lsr_max [-].
void VisitPlanets(RecordVisitor& visit, const std::vector<double>& mean,
                  const std::vector<double>& min, const std::vector<double>& max);

/// The statistics of a sweep over carrier positions (SweepSummary), the quasi-static run's and
/// the study cases': LSR per planet, K_γ, TE, the sun's displacement, stresses, friction.
void VisitRecord(const SweepSummary& summary, RecordVisitor& visit);

/// A comparison of contact back ends (solvers::RunComparison, `epicycle contact compare --json`,
/// Python's compare_backends): its settings, each back end's summary ("backends") and every
/// (back end, problem) run ("runs"), errors nondimensional. The contact core names no record
/// visitor (it knows nothing above it), so the comparison's record is visited here.
void VisitRecord(const solvers::ComparisonRecord& record, RecordVisitor& visit);

}  // namespace epicycle::transmission
