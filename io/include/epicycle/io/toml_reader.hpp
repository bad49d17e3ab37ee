// Strict reading of scene tables: every key is consumed by name, with its unit in the key;
// unknown keys, missing keys, wrong types and out-of-range values are errors that name the key,
// the value and the rule.
//
// The library epicycle_io_toml of the bottom layer io/, linked privately by the scene reader
// (transmission) and the study-file reader (studies) so that every input file has the same rules
// and messages. Its interface holds toml++ types, so it is a library of its own (the rest of io/,
// which the contact core links, links no TOML library) and not one of the installed headers.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

#include <toml++/toml.h>

namespace epicycle::io {

/// A range rule for numbers: lo/hi bounds, open or closed, in the key's unit, and why (the
/// physical reason, quoted in the message: "must be in [0, 1057.5] (a quarter module: ...)").
/// Bounds relative to the geometry are computed by the caller from values already read.
struct Rule {
  double lo = -1e300, hi = 1e300;
  bool lo_open = false, hi_open = false;
  std::string why;
  static Rule Any() { return {}; }
  static Rule Positive() { return {0, 1e300, true, false, ""}; }
  static Rule NonNegative() { return {0, 1e300, false, false, ""}; }
  static Rule Closed(double a, double b) { return {a, b, false, false, ""}; }
  static Rule HalfOpen(double a, double b) { return {a, b, false, true, ""}; }  ///< [a, b)
  static Rule Open(double a, double b) { return {a, b, true, true, ""}; }
  /// The same bounds with the reason they have.
  Rule Because(std::string reason) const {
    Rule r = *this;
    r.why = std::move(reason);
    return r;
  }
  bool Holds(double v) const;
  std::string Describe() const;
};

/// The TOML document `text`. @throws std::invalid_argument "source:line: TOML syntax error: ...".
toml::table ParseDocument(const std::string& text, const std::string& source);

class TableReader {
 public:
  TableReader(const toml::table& table, std::string path, std::string source);

  bool Has(const std::string& key) const;
  double Real(const std::string& key, Rule rule);
  double RealOr(const std::string& key, double fallback, Rule rule);
  long Integer(const std::string& key, Rule rule);
  long IntegerOr(const std::string& key, long fallback, Rule rule);
  std::string String(const std::string& key, const std::vector<std::string>& allowed = {});
  std::string StringOr(const std::string& key, const std::string& fallback,
                       const std::vector<std::string>& allowed = {});
  bool BoolOr(const std::string& key, bool fallback);
  std::vector<double> RealArray(const std::string& key, Rule rule);
  TableReader Table(const std::string& key);
  std::optional<TableReader> OptionalTable(const std::string& key);
  std::vector<TableReader> TableArray(const std::string& key);
  /// Throws if any key of the table was not read.
  void Done() const;

  const std::string& path() const { return path_; }
  /// "file:line: path.key" for messages about a key.
  std::string Where(const std::string& key) const;
  [[noreturn]] void Fail(const std::string& key, const std::string& value,
                         const std::string& rule) const;
  /// "file:line: path.key = value: rule", the text of Fail, for a warning: a legal value outside
  /// the model's validity (the caller keeps it in Scene::warnings).
  std::string Warning(const std::string& key, const std::string& rule) const;
  /// A real the reader already consumed, checked against a rule known only later (relative to the
  /// geometry read since). @throws std::invalid_argument as Real() does.
  void Check(const std::string& key, double value_in_key_unit, const Rule& rule) const;

 private:
  const toml::node* Node(const std::string& key) const;
  const toml::node& Required(const std::string& key);
  double CheckedReal(const std::string& key, const toml::node& n, Rule rule) const;

  const toml::table& table_;
  std::string path_, source_;
  std::set<std::string> used_;
  mutable std::set<std::string> known_;  // every key this reader asked about
};

}  // namespace epicycle::io
