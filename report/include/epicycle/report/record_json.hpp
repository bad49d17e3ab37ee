// A driver's record as its JSON summary: the one serialisation of every record, its keys the
// fields that the record's VisitRecord names (transmission/record.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include "epicycle/dynamics/dynamic_run.hpp"
#include "epicycle/transmission/quasistatic_run.hpp"
#include "epicycle/transmission/record.hpp"

namespace epicycle::report {

/// Builds a JSON object from a record's visit: numbers that are not finite become null (JSON has
/// no NaN), lists of objects become arrays of objects.
class JsonRecord final : public transmission::RecordVisitor {
 public:
  JsonRecord();
  void Number(const char* key, double value) override;
  void Integer(const char* key, long value) override;
  void Flag(const char* key, bool value) override;
  void Text(const char* key, const std::string& value) override;
  void Texts(const char* key, const std::vector<std::string>& value) override;
  void BeginList(const char* key) override;
  void Item() override;
  void EndList() override;
  void Stresses(const transmission::SweepSummary& summary) override;
  void Rating(const char* key, const transmission::StageRating& rating) override;
  void RootStress(const char* key, const std::vector<transmission::RootStressSummary>& gears,
                  const char* x_name, double x_scale) override;
  /// The object built so far.
  const nlohmann::json& Result() const { return root_; }

 private:
  nlohmann::json root_;
  nlohmann::json* object_;  // where the next field goes: the root or a list's last item
  nlohmann::json* list_ = nullptr;
};

/// A record's summary JSON: the fields its VisitRecord names and the program's provenance.
template <class Record>
nlohmann::json RecordJson(const Record& record, const nlohmann::json& provenance) {
  JsonRecord json;
  VisitRecord(record, json);
  nlohmann::json j = json.Result();
  j["provenance"] = provenance;
  return j;
}

/// The statistics of a sweep over carrier positions (transmission::VisitRecord(SweepSummary)).
nlohmann::json SweepSummaryJson(const transmission::SweepSummary& summary);

/// A quasi-static run's summary JSON: its record's fields and the program's provenance.
nlohmann::json QuasiStaticRecordJson(const transmission::QuasiStaticRecord& record,
                                     const nlohmann::json& provenance);

/// A dynamic run's summary JSON: its record's fields and the program's provenance.
nlohmann::json DynamicRecordJson(const dynamics::DynamicRecord& record,
                                 const nlohmann::json& provenance);

}  // namespace epicycle::report
