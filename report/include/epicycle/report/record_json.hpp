// A driver's record as its JSON summary: the one serialisation of every record, its keys the
// fields that the record's VisitRecord names (transmission/record.hpp).
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "epicycle/dynamics/dynamic_run.hpp"
#include "epicycle/dynamics/modes_run.hpp"
#include "epicycle/transmission/quasistatic_run.hpp"
#include "epicycle/transmission/record.hpp"
#include "epicycle/transmission/stiffness_run.hpp"

namespace epicycle::report {

/// Builds a JSON object from a record's visit: numbers that are not finite become null (JSON has
/// no NaN), lists of objects become arrays of objects.
class JsonRecord final : public transmission::RecordVisitor {
 public:
  JsonRecord();
  void Number(const char* key, double value) override;
  void Integer(const char* key, long value) override;
  void Unsigned(const char* key, unsigned long long value) override;
  void Flag(const char* key, bool value) override;
  void Text(const char* key, const std::string& value) override;
  void Texts(const char* key, const std::vector<std::string>& value) override;
  void Numbers(const char* key, const std::vector<double>& value) override;
  void Integers(const char* key, const std::vector<long>& value) override;
  void BeginObject(const char* key) override;
  void EndObject() override;
  void BeginList(const char* key) override;
  void Item() override;
  void EndList() override;
  void Stresses(const transmission::SweepSummary& summary) override;
  void Rating(const char* key, const transmission::StageRating& rating) override;
  void RootStress(const char* key, const std::vector<transmission::RootStressSummary>& gears,
                  const char* x_key, double x_scale) override;
  /// The object built so far.
  const nlohmann::json& Result() const { return root_; }

 private:
  nlohmann::json& Current();  // where the next field goes
  bool InItem() const;        // the innermost container is a list's item
  nlohmann::json root_;
  // The containers open, the root first: objects, lists, and a list's current item after it.
  // (A list's items are pushed only after its previous item is closed, so the pointers hold.)
  std::vector<nlohmann::json*> open_;
};

/// The statistics of a sweep over carrier positions (transmission::VisitRecord(SweepSummary)).
nlohmann::json SweepSummaryJson(const transmission::SweepSummary& summary);

/// A quasi-static run's summary JSON: its record's fields and the program's provenance.
nlohmann::json QuasiStaticRecordJson(const transmission::QuasiStaticRecord& record,
                                     const nlohmann::json& provenance);

/// Any record's fields as a JSON object (the summary JSON without the program's provenance).
template <class Record>
nlohmann::json RecordJson(const Record& record) {
  JsonRecord json;
  VisitRecord(record, json);
  return json.Result();
}

/// A run's summary JSON: its record's fields and the program's provenance.
template <class Record>
nlohmann::json SummaryJson(const Record& record, const nlohmann::json& provenance) {
  nlohmann::json j = RecordJson(record);
  j["provenance"] = provenance;
  return j;
}

/// A dynamic run's summary JSON (SummaryJson): its record's fields and the program's provenance.
nlohmann::json DynamicRecordJson(const dynamics::DynamicRecord& record,
                                 const nlohmann::json& provenance);

}  // namespace epicycle::report
