#include "epicycle/io/toml_reader.hpp"

#include "epicycle/io/number_format.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace epicycle::io {

namespace {

std::string TypeName(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    default:
      return "a date/time";
  }
}

std::string Show(const toml::node& n) {
  std::ostringstream o;
  if (n.is_string()) {
    o << '"' << n.as_string()->get() << '"';
  } else if (n.is_table()) {
    o << "{...}";
  } else if (n.is_array()) {
    o << "[...]";
  } else if (const auto* i = n.as_integer()) {
    o << i->get();
  } else if (const auto* f = n.as_floating_point()) {
    o << Num(f->get(), 10);
  } else if (const auto* b = n.as_boolean()) {
    o << (b->get() ? "true" : "false");
  } else {
    o << "(date/time)";
  }
  return o.str();
}

}  // namespace

bool Rule::Holds(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string Rule::Describe() const {
  const bool has_lo = lo > -1e299, has_hi = hi < 1e299;
  std::string text;
  if (has_lo && has_hi) {
    text = std::string("must be in ") + (lo_open ? "(" : "[") + Num(lo, 10) + ", " + Num(hi, 10) +
           (hi_open ? ")" : "]");
  } else if (has_lo) {
    text = std::string("must be ") + (lo_open ? "> " : ">= ") + Num(lo, 10);
  } else if (has_hi) {
    text = std::string("must be ") + (hi_open ? "< " : "<= ") + Num(hi, 10);
  } else {
    text = "must be a finite number";
  }
  return why.empty() ? text : text + " (" + why + ")";
}

toml::table ParseDocument(const std::string& text, const std::string& source) {
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream o;
    o << source << ":" << e.source().begin.line << ": TOML syntax error: " << e.description();
    throw std::invalid_argument(o.str());
  }
}

TableReader::TableReader(const toml::table& table, std::string path, std::string source)
    : table_(table), path_(std::move(path)), source_(std::move(source)) {}

std::string TableReader::Where(const std::string& key) const {
  // Built with a stream: GCC 12's -Wrestrict misfires on chained std::string additions here.
  std::ostringstream o;
  o << source_;
  if (const toml::node* n = Node(key)) {
    o << ':' << n->source().begin.line;
  } else if (table_.source().begin.line > 0) {
    o << ':' << table_.source().begin.line;
  }
  o << ": ";
  if (!path_.empty()) o << path_ << '.';
  o << key;
  return o.str();
}

void TableReader::Fail(const std::string& key, const std::string& value,
                       const std::string& rule) const {
  throw std::invalid_argument(Where(key) + " = " + value + ": " + rule);
}

std::string TableReader::Warning(const std::string& key, const std::string& rule) const {
  const toml::node* n = Node(key);
  return Where(key) + " = " + (n ? Show(*n) : std::string("(default)")) + ": " + rule;
}

void TableReader::Check(const std::string& key, double value, const Rule& rule) const {
  if (!rule.Holds(value)) {
    const toml::node* n = Node(key);
    Fail(key, n ? Show(*n) : Num(value, 10), rule.Describe());
  }
}

const toml::node* TableReader::Node(const std::string& key) const {
  known_.insert(key);
  return table_.get(key);
}

bool TableReader::Has(const std::string& key) const { return Node(key) != nullptr; }

const toml::node& TableReader::Required(const std::string& key) {
  const toml::node* n = Node(key);
  if (!n) throw std::invalid_argument(Where(key) + " is missing (required)");
  used_.insert(key);
  return *n;
}

double TableReader::CheckedReal(const std::string& key, const toml::node& n, Rule rule) const {
  double v;
  if (const auto* f = n.as_floating_point()) {
    v = f->get();
  } else if (const auto* i = n.as_integer()) {
    v = static_cast<double>(i->get());
  } else {
    Fail(key, Show(n), "must be a number, not " + TypeName(n));
  }
  if (!rule.Holds(v)) Fail(key, Show(n), rule.Describe());
  return v;
}

double TableReader::Real(const std::string& key, Rule rule) {
  return CheckedReal(key, Required(key), rule);
}

double TableReader::RealOr(const std::string& key, double fallback, Rule rule) {
  return Has(key) ? Real(key, rule) : fallback;
}

long TableReader::Integer(const std::string& key, Rule rule) {
  const toml::node& n = Required(key);
  const auto* i = n.as_integer();
  if (!i) Fail(key, Show(n), "must be an integer, not " + TypeName(n));
  const long v = static_cast<long>(i->get());
  if (!rule.Holds(static_cast<double>(v))) Fail(key, Show(n), rule.Describe());
  return v;
}

long TableReader::IntegerOr(const std::string& key, long fallback, Rule rule) {
  return Has(key) ? Integer(key, rule) : fallback;
}

std::string TableReader::String(const std::string& key, const std::vector<std::string>& allowed) {
  const toml::node& n = Required(key);
  const auto* s = n.as_string();
  if (!s) Fail(key, Show(n), "must be a string, not " + TypeName(n));
  const std::string v = s->get();
  if (!allowed.empty()) {
    bool ok = false;
    std::string list;
    for (const std::string& a : allowed) {
      ok = ok || a == v;
      list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
    }
    if (!ok) Fail(key, Show(n), "must be one of " + list);
  }
  return v;
}

std::string TableReader::StringOr(const std::string& key, const std::string& fallback,
                                  const std::vector<std::string>& allowed) {
  return Has(key) ? String(key, allowed) : fallback;
}

bool TableReader::BoolOr(const std::string& key, bool fallback) {
  if (!Has(key)) return fallback;
  const toml::node& n = Required(key);
  const auto* b = n.as_boolean();
  if (!b) Fail(key, Show(n), "must be true or false, not " + TypeName(n));
  return b->get();
}

std::vector<double> TableReader::RealArray(const std::string& key, Rule rule) {
  const toml::node& n = Required(key);
  const auto* a = n.as_array();
  if (!a) Fail(key, Show(n), "must be an array of numbers, not " + TypeName(n));
  std::vector<double> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    out.push_back(CheckedReal(key + "[" + std::to_string(i) + "]", *a->get(i), rule));
  }
  return out;
}

TableReader TableReader::Table(const std::string& key) {
  const toml::node& n = Required(key);
  const auto* t = n.as_table();
  if (!t) Fail(key, Show(n), "must be a table, not " + TypeName(n));
  return TableReader(*t, path_.empty() ? key : path_ + "." + key, source_);
}

std::optional<TableReader> TableReader::OptionalTable(const std::string& key) {
  if (!Has(key)) return std::nullopt;
  return Table(key);
}

std::vector<TableReader> TableReader::TableArray(const std::string& key) {
  std::vector<TableReader> out;
  if (!Has(key)) return out;
  const toml::node& n = Required(key);
  const auto* a = n.as_array();
  if (!a || !a->is_array_of_tables()) {
    Fail(key, Show(n),
         "must be an array of tables ([[" + (path_.empty() ? key : path_ + "." + key) + "]])");
  }
  for (std::size_t i = 0; i < a->size(); ++i) {
    out.emplace_back(*a->get(i)->as_table(),
                     (path_.empty() ? key : path_ + "." + key) + "[" + std::to_string(i) + "]",
                     source_);
  }
  return out;
}

void TableReader::Done() const {
  std::string unknown, known;
  for (const auto& [k, v] : table_) {
    const std::string key(k.str());
    if (!used_.count(key)) unknown += (unknown.empty() ? "" : ", ") + key;
  }
  if (unknown.empty()) return;
  for (const std::string& k : known_) {
    if (k.find('[') == std::string::npos) known += (known.empty() ? "" : ", ") + k;
  }
  const std::string first = unknown.substr(0, unknown.find(','));
  throw std::invalid_argument(Where(first) + ": unknown key" +
                              (unknown.find(',') != std::string::npos ? "s " + unknown : "") +
                              " (known keys here: " + (known.empty() ? "nothing" : known) + ")");
}

}  // namespace epicycle::io
