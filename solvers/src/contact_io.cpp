// JSON problem files (format "epicycle-contact-problem", version 1).
#include "epicycle/solvers/contact_io.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "epicycle/io/input_file.hpp"

namespace epicycle::solvers {
namespace {

using nlohmann::json;

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& key, const std::string& rule) const {
    throw std::invalid_argument("contact problem file " + source_ + ": key '" + key + "': " + rule);
  }

  double Number(const json& j, const std::string& key) const {
    if (!j.is_number()) Fail(key, "must be a number, found " + std::string(j.type_name()));
    return j.get<double>();
  }

  Eigen::VectorXd Vector(const json& j, const std::string& key) const {
    if (!j.is_array()) Fail(key, "must be an array of numbers");
    Eigen::VectorXd v(static_cast<Eigen::Index>(j.size()));
    for (std::size_t i = 0; i < j.size(); ++i)
      v(static_cast<Eigen::Index>(i)) = Number(j[i], key + "[" + std::to_string(i) + "]");
    return v;
  }

  Eigen::MatrixXd Matrix(const json& j, const std::string& key, Eigen::Index cols_if_empty) const {
    if (!j.is_array()) Fail(key, "must be an array of rows");
    if (j.empty()) return Eigen::MatrixXd(0, cols_if_empty);
    const std::size_t cols = j[0].is_array() ? j[0].size() : 0;
    Eigen::MatrixXd m(static_cast<Eigen::Index>(j.size()), static_cast<Eigen::Index>(cols));
    for (std::size_t r = 0; r < j.size(); ++r) {
      const std::string rk = key + "[" + std::to_string(r) + "]";
      if (!j[r].is_array()) Fail(rk, "must be an array (a row)");
      if (j[r].size() != cols)
        Fail(rk, "has " + std::to_string(j[r].size()) + " entries but row 0 has " +
                     std::to_string(cols) + ": rows must have equal length");
      for (std::size_t c = 0; c < cols; ++c)
        m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) =
            Number(j[r][c], rk + "[" + std::to_string(c) + "]");
    }
    return m;
  }

  std::vector<std::string> Strings(const json& j, const std::string& key) const {
    if (!j.is_array()) Fail(key, "must be an array of strings");
    std::vector<std::string> out;
    for (std::size_t i = 0; i < j.size(); ++i) {
      if (!j[i].is_string()) Fail(key + "[" + std::to_string(i) + "]", "must be a string");
      out.push_back(j[i].get<std::string>());
    }
    return out;
  }

  void OnlyKeys(const json& j, const std::string& where,
                const std::set<std::string>& allowed) const {
    if (!j.is_object()) Fail(where, "must be an object");
    for (const auto& [k, v] : j.items())
      if (!allowed.count(k)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        Fail(where.empty() ? k : where + "." + k, "unknown key (allowed: " + list + ")");
      }
  }

  const json& Required(const json& j, const std::string& key) const {
    if (!j.contains(key)) Fail(key, "missing (required)");
    return j.at(key);
  }

 private:
  std::string source_;
};

json VectorJson(const Eigen::VectorXd& v) {
  json a = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v(i));
  return a;
}

json MatrixJson(const Eigen::MatrixXd& m) {
  json a = json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) a.push_back(VectorJson(m.row(r).transpose()));
  return a;
}

}  // namespace

ContactProblemFile ParseContactProblemFile(const std::string& text, const std::string& source) {
  Reader rd(source);
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    // parse_error, and out_of_range for a number beyond double (found by fuzzing: 1e8500).
    throw std::invalid_argument("contact problem file " + source + ": not valid JSON: " + e.what());
  }
  rd.OnlyKeys(j, "",
              {"format", "version", "name", "category", "description", "seed", "compliance_m_per_N",
               "overlap_m", "equality_matrix", "equality_rhs", "support_stiffness_N_per_m",
               "support_compliance", "local", "contact_labels", "multiplier_labels", "expected",
               "provenance"});
  const json& fmt = rd.Required(j, "format");
  if (!fmt.is_string() || fmt.get<std::string>() != kContactFileFormat)
    rd.Fail("format", "must be \"" + std::string(kContactFileFormat) + "\", found " + fmt.dump());
  const json& ver = rd.Required(j, "version");
  if (!ver.is_number_integer() || ver.get<int>() != kContactFileVersion)
    rd.Fail("version", "this program reads version " + std::to_string(kContactFileVersion) +
                           ", found " + ver.dump());

  ContactProblemFile f;
  ContactProblemData& d = f.data;
  if (j.contains("name")) {
    if (!j["name"].is_string()) rd.Fail("name", "must be a string");
    d.name = j["name"].get<std::string>();
  }
  if (j.contains("category")) {
    if (!j["category"].is_string()) rd.Fail("category", "must be a string");
    f.category = j["category"].get<std::string>();
  }
  if (j.contains("description")) {
    if (!j["description"].is_string()) rd.Fail("description", "must be a string");
    f.description = j["description"].get<std::string>();
  }
  if (j.contains("provenance")) {
    const json& p = j["provenance"];
    if (!p.is_object()) rd.Fail("provenance", "must be an object of strings");
    for (const auto& [k, v] : p.items()) {
      if (!v.is_string()) rd.Fail("provenance." + k, "must be a string");
      f.provenance[k] = v.get<std::string>();
    }
  }
  if (j.contains("seed")) {
    if (!j["seed"].is_number_unsigned()) rd.Fail("seed", "must be a non-negative integer");
    f.seed = j["seed"].get<std::uint64_t>();
  }
  d.overlap = rd.Vector(rd.Required(j, "overlap_m"), "overlap_m");
  const Eigen::Index n = d.overlap.size();
  d.compliance = rd.Matrix(rd.Required(j, "compliance_m_per_N"), "compliance_m_per_N", n);
  if (j.contains("equality_rhs")) d.equality_rhs = rd.Vector(j["equality_rhs"], "equality_rhs");
  d.equality_matrix = j.contains("equality_matrix")
                          ? rd.Matrix(j["equality_matrix"], "equality_matrix", n)
                          : Eigen::MatrixXd(0, n);
  // "support_compliance" is the first name of this key: its values always entered the equations
  // as the stiffness K of G F + K λ = W, so a file that has it reads the same numbers.
  if (j.contains("support_stiffness_N_per_m") && j.contains("support_compliance"))
    rd.Fail("support_compliance",
            "give support_stiffness_N_per_m only (support_compliance is its old name)");
  if (j.contains("support_stiffness_N_per_m"))
    d.support_stiffness = rd.Matrix(j["support_stiffness_N_per_m"], "support_stiffness_N_per_m", 0);
  else if (j.contains("support_compliance"))
    d.support_stiffness = rd.Matrix(j["support_compliance"], "support_compliance", 0);
  if (j.contains("contact_labels"))
    d.contact_labels = rd.Strings(j["contact_labels"], "contact_labels");
  if (j.contains("multiplier_labels"))
    d.multiplier_labels = rd.Strings(j["multiplier_labels"], "multiplier_labels");
  if (j.contains("local")) {
    const json& loc = j["local"];
    if (!loc.is_array()) rd.Fail("local", "must be an array of local-term objects");
    for (std::size_t i = 0; i < loc.size(); ++i) {
      const std::string key = "local[" + std::to_string(i) + "]";
      const json& e = loc[i];
      rd.OnlyKeys(e, key, {"enabled", "face_width_m", "reduced_radius_m", "plane", "bodies"});
      LocalTermParameters p;
      if (e.contains("enabled")) {
        if (!e["enabled"].is_boolean()) rd.Fail(key + ".enabled", "must be true or false");
        p.enabled = e["enabled"].get<bool>();
      }
      p.face_width = rd.Number(rd.Required(e, "face_width_m"), key + ".face_width_m");
      p.reduced_radius = rd.Number(rd.Required(e, "reduced_radius_m"), key + ".reduced_radius_m");
      if (e.contains("plane")) {
        const std::string plane = e["plane"].is_string() ? e["plane"].get<std::string>() : "";
        if (const auto a = io::ValueOf(kPlaneAssumptionNames, plane))
          p.plane = *a;
        else
          rd.Fail(key + ".plane", "must be \"strain\" or \"stress\", found " + e["plane"].dump());
      }
      const json& bodies = rd.Required(e, "bodies");
      if (!bodies.is_array() || bodies.size() != 2)
        rd.Fail(key + ".bodies", "must be an array of 2 bodies");
      for (int b = 0; b < 2; ++b) {
        const std::string bk = key + ".bodies[" + std::to_string(b) + "]";
        const json& bj = bodies[static_cast<std::size_t>(b)];
        rd.OnlyKeys(bj, bk, {"youngs_modulus_Pa", "poisson_ratio", "depth_m"});
        p.body[b].youngs_modulus =
            rd.Number(rd.Required(bj, "youngs_modulus_Pa"), bk + ".youngs_modulus_Pa");
        p.body[b].poisson_ratio =
            rd.Number(rd.Required(bj, "poisson_ratio"), bk + ".poisson_ratio");
        p.body[b].depth = rd.Number(rd.Required(bj, "depth_m"), bk + ".depth_m");
      }
      d.local.push_back(p);
    }
  }
  if (j.contains("expected")) {
    const json& e = j["expected"];
    rd.OnlyKeys(e, "expected", {"force_N", "multiplier", "note"});
    ContactSolution s;
    s.force = rd.Vector(rd.Required(e, "force_N"), "expected.force_N");
    s.multiplier = e.contains("multiplier") ? rd.Vector(e["multiplier"], "expected.multiplier")
                                            : Eigen::VectorXd();
    if (e.contains("note") && e["note"].is_string()) f.expected_note = e["note"].get<std::string>();
    if (s.force.size() != n)
      rd.Fail("expected.force_N", "must have N = " + std::to_string(n) + " entries");
    if (s.multiplier.size() != d.equality_rhs.size())
      rd.Fail("expected.multiplier",
              "must have m = " + std::to_string(d.equality_rhs.size()) + " entries");
    f.expected = s;
  }
  try {
    ContactProblem check(d);  // the full validation, messages naming the field
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("contact problem file " + source + ": " + e.what());
  }
  return f;
}

ContactProblemFile ReadContactProblemFile(const std::string& path) {
  // A problem holds its dense compliance matrix: 256 MiB is a problem of thousands of contacts.
  std::string text;
  try {
    text = io::ReadInputFile(path, "problem file (JSON)", 256u << 20);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("contact problem file ") + e.what());
  }
  return ParseContactProblemFile(text, path);
}

std::string FormatContactProblemFile(const ContactProblemFile& f) {
  ContactProblem check(f.data);
  const ContactProblemData& d = f.data;
  json j;
  j["format"] = kContactFileFormat;
  j["version"] = kContactFileVersion;
  j["name"] = d.name;
  j["category"] = f.category;
  j["description"] = f.description;
  if (f.seed) j["seed"] = *f.seed;
  if (!f.provenance.empty()) j["provenance"] = f.provenance;
  j["compliance_m_per_N"] = MatrixJson(d.compliance);
  j["overlap_m"] = VectorJson(d.overlap);
  if (d.equality_rhs.size() > 0) {
    j["equality_matrix"] = MatrixJson(d.equality_matrix);
    j["equality_rhs"] = VectorJson(d.equality_rhs);
  }
  if (d.support_stiffness.size() > 0)
    j["support_stiffness_N_per_m"] = MatrixJson(d.support_stiffness);
  if (!d.local.empty()) {
    json loc = json::array();
    for (const LocalTermParameters& p : d.local) {
      json e;
      e["enabled"] = p.enabled;
      e["face_width_m"] = p.face_width;
      e["reduced_radius_m"] = p.reduced_radius;
      e["plane"] = io::NameOf(kPlaneAssumptionNames, p.plane);
      for (int b = 0; b < 2; ++b)
        e["bodies"].push_back({{"youngs_modulus_Pa", p.body[b].youngs_modulus},
                               {"poisson_ratio", p.body[b].poisson_ratio},
                               {"depth_m", p.body[b].depth}});
      loc.push_back(e);
    }
    j["local"] = loc;
  }
  if (!d.contact_labels.empty()) j["contact_labels"] = d.contact_labels;
  if (!d.multiplier_labels.empty()) j["multiplier_labels"] = d.multiplier_labels;
  if (f.expected) {
    j["expected"]["force_N"] = VectorJson(f.expected->force);
    j["expected"]["multiplier"] = VectorJson(f.expected->multiplier);
    j["expected"]["note"] = f.expected_note;
  }
  return j.dump(1) + "\n";
}

void WriteContactProblemFile(const ContactProblemFile& f, const std::string& path) {
  const std::string text = FormatContactProblemFile(f);
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write contact problem file " + path);
  out << text;
  if (!out) throw std::runtime_error("error while writing contact problem file " + path);
}

std::vector<std::string> ListProblemFiles(const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  for (const std::string& in : inputs) {
    if (fs::is_directory(in)) {
      std::vector<std::string> here;
      for (const auto& e : fs::directory_iterator(in))
        if (e.path().extension() == ".json" && e.path().filename() != "expected_failures.json")
          here.push_back(e.path().string());
      std::sort(here.begin(), here.end());
      files.insert(files.end(), here.begin(), here.end());
    } else {
      files.push_back(in);
    }
  }
  if (files.empty()) throw std::invalid_argument("no problem files found in the given paths");
  return files;
}

}  // namespace epicycle::solvers
