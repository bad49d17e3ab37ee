// Records as JSON (record_json.hpp).
#include "epicycle/report/record_json.hpp"

#include <stdexcept>

#include "epicycle/geometry/plane.hpp"
#include "epicycle/report/ratings.hpp"
#include "epicycle/report/run_files.hpp"

namespace epicycle::report {

JsonRecord::JsonRecord() : root_(nlohmann::json::object()), open_{&root_} {}

nlohmann::json& JsonRecord::Current() {
  if (!open_.back()->is_object())
    throw std::logic_error("JsonRecord: a field in a list outside an item");
  return *open_.back();
}

bool JsonRecord::InItem() const {
  return open_.size() >= 2 && open_.back()->is_object() && open_[open_.size() - 2]->is_array();
}

void JsonRecord::Number(const char* key, double value) { Current()[key] = JsonValue(value); }
void JsonRecord::Integer(const char* key, long value) { Current()[key] = value; }
void JsonRecord::Unsigned(const char* key, unsigned long long value) { Current()[key] = value; }
void JsonRecord::Flag(const char* key, bool value) { Current()[key] = value; }
void JsonRecord::Text(const char* key, const std::string& value) { Current()[key] = value; }
void JsonRecord::Texts(const char* key, const std::vector<std::string>& value) {
  Current()[key] = nlohmann::json(value);  // [] when empty
}
void JsonRecord::Numbers(const char* key, const std::vector<double>& value) {
  nlohmann::json list = nlohmann::json::array();
  for (const double v : value) list.push_back(JsonValue(v));
  Current()[key] = std::move(list);
}

void JsonRecord::Integers(const char* key, const std::vector<long>& value) {
  Current()[key] = nlohmann::json(value);  // [] when empty
}

void JsonRecord::BeginList(const char* key) {
  open_.push_back(&(Current()[key] = nlohmann::json::array()));
}

void JsonRecord::Item() {
  if (InItem()) open_.pop_back();
  if (!open_.back()->is_array()) throw std::logic_error("JsonRecord: an item outside a list");
  open_.back()->push_back(nlohmann::json::object());
  open_.push_back(&open_.back()->back());
}

void JsonRecord::EndList() {
  if (InItem()) open_.pop_back();
  if (!open_.back()->is_array()) throw std::logic_error("JsonRecord: EndList outside a list");
  open_.pop_back();
}

void JsonRecord::BeginObject(const char* key) {
  open_.push_back(&(Current()[key] = nlohmann::json::object()));
}

void JsonRecord::EndObject() {
  if (open_.size() < 2 || InItem() || !open_.back()->is_object())
    throw std::logic_error("JsonRecord: EndObject outside an object");
  open_.pop_back();
}

void JsonRecord::Stresses(const transmission::SweepSummary& s) {
  if (!s.root_stress.empty())
    Current()["root_stress"] = RootStressJson(s.root_stress, "carrier_deg", geometry::Deg(1.0));
  if (!s.contact_pressure.empty())
    Current()["contact_pressure"] =
        ContactPressureJson(s.contact_pressure, "carrier_deg", geometry::Deg(1.0));
}

void JsonRecord::Rating(const char* key, const transmission::StageRating& rating) {
  Current()[key] = RatingJson(rating);
}

void JsonRecord::RootStress(const char* key,
                            const std::vector<transmission::RootStressSummary>& gears,
                            const char* x_key, double x_scale) {
  Current()[key] = RootStressJson(gears, x_key, x_scale);
}


nlohmann::json SweepSummaryJson(const transmission::SweepSummary& summary) {
  JsonRecord json;
  transmission::VisitRecord(summary, json);
  return json.Result();
}

nlohmann::json QuasiStaticRecordJson(const transmission::QuasiStaticRecord& record,
                                     const nlohmann::json& provenance) {
  return SummaryJson(record, provenance);
}

nlohmann::json DynamicRecordJson(const dynamics::DynamicRecord& record,
                                 const nlohmann::json& provenance) {
  return SummaryJson(record, provenance);
}

}  // namespace epicycle::report
