// Records as JSON (record_json.hpp).
#include "epicycle/report/record_json.hpp"

#include <stdexcept>

#include "epicycle/geometry/plane.hpp"
#include "epicycle/report/ratings.hpp"
#include "epicycle/report/run_files.hpp"

namespace epicycle::report {

JsonRecord::JsonRecord() : root_(nlohmann::json::object()), object_(&root_) {}

void JsonRecord::Number(const char* key, double value) { (*object_)[key] = JsonValue(value); }
void JsonRecord::Integer(const char* key, long value) { (*object_)[key] = value; }
void JsonRecord::Flag(const char* key, bool value) { (*object_)[key] = value; }
void JsonRecord::Text(const char* key, const std::string& value) { (*object_)[key] = value; }
void JsonRecord::Texts(const char* key, const std::vector<std::string>& value) {
  (*object_)[key] = nlohmann::json(value);  // [] when empty
}

void JsonRecord::BeginList(const char* key) {
  if (list_ != nullptr) throw std::logic_error("JsonRecord: a list inside a list");
  list_ = &((*object_)[key] = nlohmann::json::array());
}

void JsonRecord::Item() {
  if (list_ == nullptr) throw std::logic_error("JsonRecord: an item outside a list");
  list_->push_back(nlohmann::json::object());
  object_ = &list_->back();
}

void JsonRecord::EndList() {
  list_ = nullptr;
  object_ = &root_;
}

void JsonRecord::Stresses(const transmission::SweepSummary& s) {
  if (!s.root_stress.empty())
    (*object_)["root_stress"] = RootStressJson(s.root_stress, "carrier_deg", geometry::Deg(1.0));
  if (!s.contact_pressure.empty())
    (*object_)["contact_pressure"] =
        ContactPressureJson(s.contact_pressure, "carrier_deg", geometry::Deg(1.0));
}

void JsonRecord::Rating(const char* key, const transmission::StageRating& rating) {
  (*object_)[key] = RatingJson(rating);
}

void JsonRecord::RootStress(const char* key,
                            const std::vector<transmission::RootStressSummary>& gears,
                            const char* x_name, double x_scale) {
  (*object_)[key] = RootStressJson(gears, x_name, x_scale);
}

nlohmann::json SweepSummaryJson(const transmission::SweepSummary& summary) {
  JsonRecord json;
  transmission::VisitRecord(summary, json);
  return json.Result();
}

nlohmann::json QuasiStaticRecordJson(const transmission::QuasiStaticRecord& record,
                                     const nlohmann::json& provenance) {
  return RecordJson(record, provenance);
}

nlohmann::json DynamicRecordJson(const dynamics::DynamicRecord& record,
                                 const nlohmann::json& provenance) {
  return RecordJson(record, provenance);
}

}  // namespace epicycle::report
