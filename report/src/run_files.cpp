#include "epicycle/report/run_files.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/report/provenance.hpp"
#include "epicycle/report/ratings.hpp"
#include "epicycle/report/svg_plot.hpp"
#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/io/units.hpp"

namespace epicycle::report {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Appends ",<v>" (Cell: an empty cell where v is not finite).
void CommaCell(std::string& line, double v) {
  line += ',';
  AppendCell(line, v);
}

// "mesh,kind,flank" of a contact: the text cells of a pairs file's line.
std::string PairCells(const transmission::StageContact& c) {
  return CsvText(geometry::MeshName(c.planet, c.mesh)) + "," +
         CsvText(geometry::KindName(c.contact.kind)) + "," + CsvText(c.FlankName());
}

// "a,b,c" of the values formatted by Cell (empty cells where not finite), each led by a comma.
template <typename Range>
std::string Cells(const Range& values) {
  std::string s;
  for (double v : values) CommaCell(s, v);
  return s;
}

// ",sigma_t_<gear>_MPa,sigma_c_<gear>_MPa" for each gear of `gears` (body order); with `where`
// each stress is followed by its place: ",..._tooth,..._fillet,..._arc_mm".
std::string RootStressHead(const std::vector<std::string>& gears, bool where = false) {
  std::string head;
  for (const std::string& gear : gears)
    for (const char* kind : {"sigma_t_", "sigma_c_"}) {
      const std::string name = kind + gear;
      head += "," + name + "_MPa";
      if (where) head += "," + name + "_tooth," + name + "_fillet," + name + "_arc_mm";
    }
  return head;
}

// Each body's largest tension and compression [MPa] of a state (`g`: its extremes, body order;
// with `where`, each followed by its tooth, fillet side + or - and arc length from the space
// centre line [mm], empty for a gear the state does not load); empty cells for a state without
// them (`g` empty: a failed position).
void RootStressCells(std::string& line, const std::vector<transmission::GearRootStress>& g,
                     int bodies, bool where = false) {
  if (!g.empty() && g.size() != static_cast<std::size_t>(bodies))
    throw std::invalid_argument(fmt::format(
        "root stress cells: extremes of {} bodies for {} columns' bodies", g.size(), bodies));
  auto cells = [&](double sigma, const transmission::FilletSpot& at) {
    CommaCell(line, sigma / 1e6);
    if (!where) return;
    if (std::isfinite(sigma) && sigma != 0.0)
      line +=
          fmt::format(",{},{},{}", at.tooth, at.side == 0 ? "+" : "-", Cell(at.arc_length * 1e3));
    else
      line += ",,,";
  };
  for (int b = 0; b < bodies; ++b) {
    const transmission::GearRootStress none{b, NAN, {}, NAN, {}};
    const transmission::GearRootStress& e = g.empty() ? none : g[static_cast<std::size_t>(b)];
    cells(e.tension, e.tension_at);
    cells(e.compression, e.compression_at);
  }
}

// Per planet its LSR mean, min and max [-] (null where there is none).
}  // namespace

BinEnvelope::BinEnvelope(int values, double origin, double width)
    : values_(values), origin_(origin), width_(width) {
  if (values < 1 || !(width > 0) || !std::isfinite(width) || !std::isfinite(origin))
    throw std::invalid_argument(fmt::format(
        "BinEnvelope: {} values, bins of width {} from {}: need >= 1 value and a positive, finite "
        "width",
        values, width, origin));
}

void BinEnvelope::Add(double x, const std::vector<double>& values) {
  const auto key = static_cast<long>(std::floor((x - origin_) / width_));
  if (open_.count > 0 && key != key_) {
    closed_.push_back(Close(open_));
    open_.count = 0;
  }
  if (open_.count == 0) {
    key_ = key;
    open_.x_first = x;
    open_.x_mean = 0;
    open_.mean.assign(static_cast<std::size_t>(values_), 0.0);
    open_.min = values;
    open_.max = values;
  }
  ++open_.count;
  open_.x_last = x;
  open_.x_mean += x;
  for (std::size_t k = 0; k < open_.mean.size(); ++k) {
    open_.mean[k] += values[k];
    open_.min[k] = std::min(open_.min[k], values[k]);
    open_.max[k] = std::max(open_.max[k], values[k]);
  }
}

BinEnvelope::Bin BinEnvelope::Close(const Bin& open) const {
  Bin b = open;
  const auto n = static_cast<double>(b.count);
  b.x_mean /= n;
  for (double& m : b.mean) m /= n;
  return b;
}

std::vector<BinEnvelope::Bin> BinEnvelope::Bins() const {
  std::vector<Bin> out = closed_;
  if (open_.count > 0) out.push_back(Close(open_));
  return out;
}

// The three figures of a run of a stage against x (carrier angle or time): LSR_i, the
// transmission error at the sun [µrad], and the sun centre's path [µm] (equal axes). With `bin`
// > 1 (a long run), each run of `bin` states adds its lowest and highest point of each series (in
// their order) and the path its points nearest to and farthest from the origin, so that a peak
// narrower than a bin still shows while the figures hold a bounded number of points. With an
// envelope (`envelope_width` > 0, bins of mesh cycles named `envelope_name`), LSR_i and TE are
// drawn as their mean per bin over the band from lowest to highest, and the path's mean per bin
// over the raw path.
class RunFigures {
 public:
  RunFigures(std::string base, int planets, std::string x_label, long bin = 1,
             double envelope_width = 0, std::string envelope_name = "")
      : base_(std::move(base)),
        planets_(planets),
        x_label_(std::move(x_label)),
        envelope_name_(std::move(envelope_name)),
        bin_(bin) {
    for (int i = 0; i < planets_; ++i) {
      lsr_.push_back({fmt::format("planet {}", i + 1), {}, {}});
      lsr_bin_.emplace_back();
    }
    if (envelope_width > 0) envelope_.emplace(planets_ + 3, 0.0, envelope_width);
  }
  void Add(double x, const std::vector<double>& load_sharing, double te_rad, double sun_x,
           double sun_y) {
    if (envelope_) {
      values_.assign(load_sharing.begin(), load_sharing.end());
      values_.resize(static_cast<std::size_t>(planets_));
      values_.push_back(te_rad * 1e6);
      values_.push_back(sun_x * 1e6);
      values_.push_back(sun_y * 1e6);
      envelope_->Add(x, values_);
    }
    if (bin_ <= 1) {
      for (int i = 0; i < planets_; ++i) {
        lsr_[i].x.push_back(x);
        lsr_[i].y.push_back(load_sharing[i]);
      }
      te_.x.push_back(x);
      te_.y.push_back(te_rad * 1e6);
      path_.x.push_back(sun_x * 1e6);
      path_.y.push_back(sun_y * 1e6);
      return;
    }
    if (states_ > 0 && states_ % bin_ == 0) Flush();
    ++states_;
    for (int i = 0; i < planets_; ++i) lsr_bin_[i].Add(states_, x, load_sharing[i], load_sharing[i]);
    te_bin_.Add(states_, x, te_rad * 1e6, te_rad);
    path_bin_.Add(states_, sun_x * 1e6, sun_y * 1e6, std::hypot(sun_x, sun_y));
  }
  void Write(const std::string& lsr_title, const std::string& te_title,
             const std::string& path_title, const std::string& path_file) {
    Flush();
    LinePlot l{lsr_title, x_label_, "LSR_i [-]", lsr_, false, {1.0 / planets_}};
    std::string lsr_svg;  // the envelope's panels, else `l`
    LinePlot t{te_title, x_label_, "sun rotation from kinematic [urad]", {te_}, false, {}};
    LinePlot p{path_title, "x [um]", "y [um]", {path_}, true, {}};
    if (envelope_) {
      // A partial bin at either end (fewer than half the fullest bin's states) is not drawn.
      std::vector<BinEnvelope::Bin> bins = envelope_->Bins();
      long full = 0;
      for (const BinEnvelope::Bin& b : bins) full = std::max(full, b.count);
      std::erase_if(bins, [&](const BinEnvelope::Bin& b) { return 2 * b.count < full; });
      const std::string per = "mean per " + envelope_name_ + ", band: lowest to highest";
      // One panel per planet on one scale: each planet's band can span most of the others'
      // (a floating sun's planets swing through the same range within every mesh cycle).
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const BinEnvelope::Bin& b : bins) {
        for (int i = 0; i < planets_; ++i) {
          lo = std::min(lo, b.min[static_cast<std::size_t>(i)]);
          hi = std::max(hi, b.max[static_cast<std::size_t>(i)]);
        }
      }
      lo = std::min(lo, 1.0 / planets_);
      hi = std::max(hi, 1.0 / planets_);
      const double pad = 0.05 * std::max(hi - lo, 1e-9);
      std::vector<LinePlot> panels;
      for (int i = 0; i < planets_; ++i) {
        // The x label under the last panel only.
        LinePlot panel{fmt::format("planet {} ({})", i + 1, per),
                       i + 1 == planets_ ? x_label_ : "",
                       fmt::format("LSR_{} [-]", i + 1),
                       {Band(bins, i, i), Mean(bins, i, "mean", i)},
                       false,
                       {1.0 / planets_}};
        panel.height = 260;
        panel.y_min = lo - pad;
        panel.y_max = hi + pad;
        panels.push_back(std::move(panel));
      }
      lsr_svg = RenderSvgStack(lsr_title, panels);
      t.series = {Band(bins, planets_, 0), Mean(bins, planets_, "TE", 0)};
      t.y_label += " (" + per + ")";
      PlotSeries raw = path_;
      raw.faint = true;
      PlotSeries mean{"mean per " + envelope_name_, {}, {}};
      mean.colour = 1;
      for (const BinEnvelope::Bin& b : bins) {
        mean.x.push_back(b.mean[static_cast<std::size_t>(planets_) + 1]);
        mean.y.push_back(b.mean[static_cast<std::size_t>(planets_) + 2]);
      }
      p.series = {raw, mean};
    }
    WriteTextFile(base_ + "_lsr.svg", lsr_svg.empty() ? RenderSvg(l) : lsr_svg);
    WriteTextFile(base_ + "_te.svg", RenderSvg(t));
    WriteTextFile(base_ + path_file, RenderSvg(p));
  }

 private:
  // Value k of the bins: lowest forwards, highest backwards, as one band.
  static PlotSeries Band(const std::vector<BinEnvelope::Bin>& bins, int k, int colour) {
    PlotSeries b{"", {}, {}};
    b.band = true;
    b.colour = colour;
    const auto v = static_cast<std::size_t>(k);
    for (const BinEnvelope::Bin& bin : bins) {
      b.x.push_back(bin.x_mean);
      b.y.push_back(bin.min[v]);
    }
    for (auto it = bins.rbegin(); it != bins.rend(); ++it) {
      b.x.push_back(it->x_mean);
      b.y.push_back(it->max[v]);
    }
    return b;
  }
  static PlotSeries Mean(const std::vector<BinEnvelope::Bin>& bins, int k, std::string name,
                         int colour) {
    PlotSeries m{std::move(name), {}, {}};
    m.colour = colour;
    for (const BinEnvelope::Bin& bin : bins) {
      m.x.push_back(bin.x_mean);
      m.y.push_back(bin.mean[static_cast<std::size_t>(k)]);
    }
    return m;
  }
  // One series' points of the current bin with the smallest and largest key.
  struct Extremes {
    struct Point {
      long state = 0;
      double x = 0, y = 0, key = 0;
    };
    Point low, high;
    bool empty = true;
    void Add(long state, double x, double y, double key) {
      const Point p{state, x, y, key};
      if (empty || key < low.key) low = p;
      if (empty || key > high.key) high = p;
      empty = false;
    }
    void MoveTo(PlotSeries& series) {
      if (empty) return;
      const Point& first = low.state <= high.state ? low : high;
      const Point& second = low.state <= high.state ? high : low;
      series.x.push_back(first.x);
      series.y.push_back(first.y);
      if (second.state != first.state) {
        series.x.push_back(second.x);
        series.y.push_back(second.y);
      }
      empty = true;
    }
  };
  void Flush() {
    for (int i = 0; i < planets_; ++i) lsr_bin_[i].MoveTo(lsr_[i]);
    te_bin_.MoveTo(te_);
    path_bin_.MoveTo(path_);
  }

  std::string base_;
  int planets_ = 0;
  std::string x_label_, envelope_name_;
  long bin_ = 1, states_ = 0;
  std::vector<PlotSeries> lsr_;
  PlotSeries te_{"TE", {}, {}}, path_{"sun centre", {}, {}};
  std::vector<Extremes> lsr_bin_;
  Extremes te_bin_, path_bin_;
  std::optional<BinEnvelope> envelope_;
  std::vector<double> values_;
};

namespace {

// Bins of states for RunFigures: 1 up to kPlotPoints states, else ⌈states/(kPlotPoints/2)⌉.
long StateBin(long states) {
  const long most = QuasiStaticPlots::kPlotPoints;
  return states > most ? (states + most / 2 - 1) / (most / 2) : 1;
}

// The envelope's bin of a run over `cycles` mesh cycles of `cycle` (in x): {width, name}, or
// {0, ""} (no envelope) below 8 cycles; ⌈cycles/(kPlotPoints/2)⌉ cycles a bin.
std::pair<double, std::string> CycleBin(double cycle, double cycles) {
  if (!(cycle > 0) || !(cycles >= 8)) return {0.0, ""};
  const double per = std::max(1.0, std::ceil(cycles / (QuasiStaticPlots::kPlotPoints / 2)));
  return {cycle * per, per == 1 ? "mesh cycle" : fmt::format("{:g} mesh cycles", per)};
}

}  // namespace

nlohmann::json JsonValue(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}

QuasiStaticFiles::QuasiStaticFiles(const std::string& base, const nlohmann::json& provenance,
                                   int planets, bool friction, bool root_stress)
    : positions_(base + "_positions.csv"),
      pairs_(base + "_pairs.csv"),
      friction_(friction),
      bodies_(root_stress ? transmission::PlanetBody(planets) : 0) {
  std::string head = ProvenanceCsvLine(provenance) + "carrier_deg,converged";
  for (int i = 1; i <= planets; ++i) head += ",LSR_" + std::to_string(i);
  for (int i = 1; i <= planets; ++i) head += ",L_" + std::to_string(i);
  head +=
      ",K_gamma,transmission_error_urad,sun_x_um,sun_y_um,geometric_iterations,"
      "contact_iterations,warm_started,residual,status,active_contacts,contacts,solve_ms,"
      "message";
  if (friction_) head += ",friction_power_W,input_power_W,output_power_W,efficiency,force_change";
  head += RootStressHead(transmission::BodyNames(bodies_));
  positions_.Write(head + "\n");
  pairs_.Write(ProvenanceCsvLine(provenance) + "carrier_deg,mesh,kind,flank,teeth,force_N" +
               (friction_ ? ",friction_N,sliding_m_per_s" : "") +
               (bodies_ > 0 ? ",hertz_pressure_MPa,hertz_half_width_um\n" : "\n"));
}

void QuasiStaticFiles::Write(const transmission::PositionResult& r) {
  const double deg = geometry::Deg(r.carrier_angle);
  const bool ok = r.converged;
  std::string line = fmt::format("{:.6f},{}", deg, ok ? 1 : 0);
  const std::vector<double> l = transmission::LoadSharingFactors(r);
  for (double v : r.load_sharing) CommaCell(line, ok ? v : NAN);
  for (double v : l) CommaCell(line, ok ? v : NAN);
  line += fmt::format(
      ",{},{},{},{},{},{},{},{},{},{},{},{},{}", Cell(ok ? transmission::MeshLoadFactor(r) : NAN),
      Cell(ok ? r.transmission_error * 1e6 : NAN), Cell(ok ? r.sun_displacement.x() * 1e6 : NAN),
      Cell(ok ? r.sun_displacement.y() * 1e6 : NAN), r.geometric_iterations, r.contact_iterations,
      r.warm_started ? 1 : 0, Cell(r.report.residual.total),
      CsvText(solvers::StatusName(r.report.status)), r.report.active_contacts,
      r.problem.contacts.size(), Figure(r.report.total_seconds * 1e3, "{:.4g}"),
      CsvText(r.message));
  const bool friction = friction_ && ok && r.friction;
  if (friction_)
    line += fmt::format(",{},{},{},{},{}", Cell(friction ? r.friction_power : NAN),
                        Cell(friction ? r.input_power : NAN), Cell(friction ? r.output_power : NAN),
                        Cell(friction ? r.Efficiency() : NAN), Cell(r.force_change));
  // A failed position has no stresses (empty cells), a converged one its extremes per gear.
  static const std::vector<transmission::GearRootStress> kNone;
  if (bodies_ > 0) RootStressCells(line, ok ? r.root_stress : kNone, bodies_);
  positions_.WriteLine(line);
  std::string pairs;
  for (std::size_t j = 0; j < r.problem.contacts.size() && ok; ++j) {
    const double f = r.solution.force(static_cast<Eigen::Index>(j));
    if (!(f > 0)) continue;
    const transmission::StageContact& c = r.problem.contacts[j];
    pairs += fmt::format("{:.6f},{},{}/{},{}", deg, PairCells(c), c.contact.tooth_a,
                         c.contact.tooth_b, Cell(f));
    if (friction_)
      pairs += friction ? fmt::format(",{},{}", Cell(r.friction_force(static_cast<Eigen::Index>(j))),
                                      Cell(r.sliding_velocity(static_cast<Eigen::Index>(j))))
                        : std::string(",,");
    if (bodies_ > 0) {  // stresses: Hertz's pressure and half-width of the contact
      const auto& local = r.problem.data.local;
      const bool known = j < local.size();
      CommaCell(pairs, known ? solvers::HertzPressure(local[j], f) / 1e6 : NAN);
      CommaCell(pairs, known ? solvers::HertzHalfWidth(local[j], f) * 1e6 : NAN);
    }
    pairs += '\n';
  }
  pairs_.Write(pairs);
}

void QuasiStaticFiles::Close() {
  positions_.Close();
  pairs_.Close();
}

void WriteStageProblemFile(const std::string& dir, const std::string& name,
                           const solvers::ContactProblemData& data,
                           const nlohmann::json& provenance, const std::string& description) {
  solvers::ContactProblemFile file;
  file.data = data;
  file.data.name = name;
  file.category = "stage";
  for (const auto& item : provenance.items())
    if (item.value().is_string()) file.provenance[item.key()] = item.value().get<std::string>();
  file.description = description;
  solvers::WriteContactProblemFile(file, dir + "/" + name + ".json");
}

nlohmann::json RootStressJson(const std::vector<transmission::RootStressSummary>& gears,
                              const std::string& x_name, double x_scale) {
  auto spot = [](const transmission::FilletSpot& at) {
    return nlohmann::json{{"tooth", at.tooth},
                          {"fillet", at.side == 0 ? "+" : "-"},
                          {"arc_from_space_centre_mm", at.arc_length * 1e3}};
  };
  nlohmann::json list = nlohmann::json::array();
  for (const auto& g : gears)
    list.push_back({{"gear", g.gear},
                    {"tension_MPa", g.extremes.tension / 1e6},
                    {"tension_" + x_name, g.tension_x * x_scale},
                    {"tension_at", spot(g.extremes.tension_at)},
                    {"compression_MPa", g.extremes.compression / 1e6},
                    {"compression_" + x_name, g.compression_x * x_scale},
                    {"compression_at", spot(g.extremes.compression_at)},
                    {"largest_range_MPa", g.range.range / 1e6},
                    {"largest_range_at", spot(g.range.at)},
                    {"largest_range_max_min_MPa", {g.range.max / 1e6, g.range.min / 1e6}}});
  return list;
}

std::string RootStressText(const std::vector<transmission::RootStressSummary>& gears,
                           const std::string& x_name, double x_scale) {
  if (gears.empty()) return "";
  std::string out =
      fmt::format("  root stress [MPa]  tension ({}, tooth/fillet)  compression  range\n", x_name);
  auto side = [](int s) { return s == 0 ? "+" : "-"; };
  for (const auto& g : gears) {
    const auto& e = g.extremes;
    out += fmt::format(
        "    {:<8} {:9.2f} ({:8.4g}, {}{})  {:9.2f} ({:8.4g}, {}{})  {:9.2f} ({}{})\n", g.gear,
        e.tension / 1e6, g.tension_x * x_scale, e.tension_at.tooth, side(e.tension_at.side),
        e.compression / 1e6, g.compression_x * x_scale, e.compression_at.tooth,
        side(e.compression_at.side), g.range.range / 1e6, g.range.at.tooth, side(g.range.at.side));
  }
  return out;
}

QuasiStaticPlots::QuasiStaticPlots(const std::string& base, int planets, long positions,
                                   double cycle_deg, double span_deg) {
  const auto [width, name] = CycleBin(cycle_deg, std::abs(span_deg) / cycle_deg);
  figures_ = std::make_unique<RunFigures>(base, planets, "carrier angle [deg]",
                                          StateBin(positions), width, name);
}

QuasiStaticPlots::~QuasiStaticPlots() = default;

void QuasiStaticPlots::Add(const transmission::PositionResult& r) {
  if (r.converged)
    figures_->Add(geometry::Deg(r.carrier_angle), r.load_sharing, r.transmission_error,
                  r.sun_displacement.x(), r.sun_displacement.y());
}

void QuasiStaticPlots::Write(const std::string& scene_name, const std::string& sun_name) {
  figures_->Write(scene_name + ": load-sharing ratio (sun " + sun_name + ")",
                  scene_name + ": loaded static transmission error at the sun",
                  scene_name + ": sun centre path", "_sun_path.svg");
}

namespace {

// The first lines (provenance, columns) of a dynamic run's files.
std::string DynamicStepsHead(const std::string& provenance_line, int planets, int stress_bodies,
                             const std::vector<std::string>& face_meshes, bool helical) {
  std::string steps = provenance_line + "time_s,carrier_deg";
  for (int i = 1; i <= planets; ++i) steps += ",LSR_" + std::to_string(i);
  for (int i = 1; i <= planets; ++i) steps += ",L_" + std::to_string(i);
  steps +=
      ",K_gamma,transmission_error_urad,sun_x_um,sun_y_um,sun_torque_balance_Nm,"
      "external_work_J,dissipated_work_J,kinetic_energy_J,elastic_energy_J,compliance_work_J,"
      "contacts,"
      "active_contacts,friction_power_W";
  for (int i = 1; i <= planets; ++i) steps += ",LSR_force_" + std::to_string(i);
  steps += RootStressHead(transmission::BodyNames(stress_bodies));
  for (const std::string& m : face_meshes) steps += ",K_Hbeta_" + m + ",largest_z_mm_" + m;
  if (helical) {
    steps += ",sun_axial_force_N,ring_axial_force_N,carrier_axial_force_N";
    for (int i = 1; i <= planets; ++i)
      steps += fmt::format(",sun_mesh_axial_force_N_{0},tilting_moment_radial_Nm_{0},"
                           "tilting_moment_tangential_Nm_{0}",
                           i);
  }
  return steps + "\n";
}

std::string DynamicBearingsHead(const std::string& provenance_line, int planets) {
  std::string bearings = provenance_line + "time_s,sun_Fx_N,sun_Fy_N";
  for (int i = 1; i <= planets; ++i) bearings += fmt::format(",planet{0}_Fx_N,planet{0}_Fy_N", i);
  return bearings + "\n";
}

}  // namespace

// Created in the order of a step's writes (pairs, bearings, steps), each with its head at once:
// once the steps file has its head, every file has.
DynamicRunFiles::DynamicRunFiles(const std::string& base, const nlohmann::json& provenance,
                                 int planets, bool root_stress,
                                 std::vector<std::string> face_meshes, bool helical)
    : pairs_(base + "_pairs.csv",
             ProvenanceCsvLine(provenance) +
                 "time_s,mesh,kind,flank,teeth,normal_force_N,elastic_force_N,friction_force_N,"
                 "overlap_rate_mm_per_s\n"),
      bearings_(base + "_bearings.csv",
                DynamicBearingsHead(ProvenanceCsvLine(provenance), planets)),
      steps_(base + "_steps.csv",
             DynamicStepsHead(ProvenanceCsvLine(provenance), planets,
                              root_stress ? transmission::PlanetBody(planets) : 0, face_meshes,
                              helical)),
      bodies_(root_stress ? transmission::PlanetBody(planets) : 0),
      face_meshes_(face_meshes.size()),
      helical_planets_(helical ? planets : 0) {}

void DynamicRunFiles::Write(const dynamics::DynamicSample& s) {
  const dynamics::Evaluation& e = s.evaluation;
  const auto n = static_cast<double>(s.load_sharing.size());
  std::string steps = fmt::format("{:.9g},{:.6f}", s.time, geometry::Deg(s.carrier_angle));
  steps += Cells(s.load_sharing);
  for (double v : s.load_sharing) CommaCell(steps, n * v);
  int active = 0;
  for (int j = 0; j < e.total_force.size(); ++j) active += e.total_force(j) > 0;
  steps += fmt::format(",{},{},{},{},{},{},{},{},{},{},{},{},{}", Cell(s.k_gamma),
                       Cell(s.transmission_error * 1e6), Cell(s.sun_centre.x() * 1e6),
                       Cell(s.sun_centre.y() * 1e6), Cell(s.sun_torque_balance), Cell(s.external_work),
                       Cell(s.dissipated_work), Cell(e.kinetic_energy), Cell(e.elastic_energy),
                       Cell(s.compliance_work), e.terms.size(), active, Cell(e.friction_power));
  steps += Cells(s.force_sharing);
  if (bodies_ > 0) RootStressCells(steps, s.root_stress, bodies_);
  for (std::size_t m = 0; m < face_meshes_; ++m) {
    if (m < s.face_loads.size()) {
      CommaCell(steps, s.face_loads[m].k_h_beta);
      CommaCell(steps, s.face_loads[m].largest_z * 1e3);
    } else {
      steps += ",,";  // an empty cell: no value, never a NaN
    }
  }
  if (helical_planets_ > 0) {
    const transmission::HelicalLoads& h = s.helical;
    CommaCell(steps, h.sun_axial_force);
    CommaCell(steps, h.ring_axial_force);
    CommaCell(steps, h.carrier_axial_force);
    for (int i = 0; i < helical_planets_; ++i) {
      if (static_cast<std::size_t>(i) < h.planets.size()) {
        const transmission::PlanetHelicalLoad& p = h.planets[static_cast<std::size_t>(i)];
        CommaCell(steps, p.sun_mesh_axial);
        CommaCell(steps, p.moment_radial);
        CommaCell(steps, p.moment_tangential);
      } else {
        steps += ",,,";  // no value, never a NaN
      }
    }
  }
  std::string pairs;
  for (int j = 0; j < e.terms.size(); ++j) {
    if (!(e.total_force(j) > 0)) continue;
    const transmission::StageContact& c = e.terms.contacts[j];
    pairs += fmt::format("{:.9g},{},{}/{},{},{},{},{}\n", s.time, PairCells(c), c.contact.tooth_a,
                         c.contact.tooth_b, Cell(e.total_force(j)), Cell(e.force(j)),
                         Cell(e.friction(j)), Cell(e.overlap_rate(j) * 1e3));
  }
  std::string bearings = fmt::format("{:.9g},{},{}", s.time, Cell(e.sun_bearing_force.x()),
                                     Cell(e.sun_bearing_force.y()));
  for (const auto& f : e.planet_bearing_force) {
    CommaCell(bearings, f.x());
    CommaCell(bearings, f.y());
  }
  // Each file gets the step's lines in one write; the steps line last: a step is complete when
  // its line is in BASE_steps.csv.
  pairs_.Write(pairs);
  bearings_.WriteLine(bearings);
  steps_.WriteLine(steps);
}

void DynamicRunFiles::Close() {
  steps_.Close();
  pairs_.Close();
  bearings_.Close();
}

DynamicPlots::DynamicPlots(const std::string& base, int planets, const dynamics::RunSpan& span) {
  const auto [width, name] = CycleBin(span.cycle_time * 1e3, span.duration / span.cycle_time);
  figures_ = std::make_unique<RunFigures>(base, planets, "time [ms]", StateBin(span.outputs),
                                          width, name);
}

DynamicPlots::~DynamicPlots() = default;

void DynamicPlots::Add(const dynamics::DynamicSample& s) {
  figures_->Add(s.time * 1e3, s.load_sharing, s.transmission_error, s.sun_centre.x(),
                s.sun_centre.y());
}

void DynamicPlots::Write(const std::string& scene_name, const std::string& sun_name) {
  figures_->Write(scene_name + ": dynamic load-sharing ratio (sun " + sun_name + ")",
                  scene_name + ": dynamic transmission error at the sun",
                  scene_name + ": sun centre orbit", "_orbit.svg");
}

std::string DynamicRunText(const dynamics::DynamicSummary& sum,
                           const dynamics::SimulationStats& st, int n) {
  std::string t = fmt::format(
      "\n  planet   LSR mean     LSR min      LSR max      (ideal 1/n = {:.6f})\n", 1.0 / n);
  for (int i = 0; i < n && sum.samples > 0; ++i)
    t += fmt::format("  {:<8} {:<12.6f} {:<12.6f} {:<12.6f}\n", i + 1, sum.lsr_mean[i],
                     sum.lsr_min[i], sum.lsr_max[i]);
  // No output step: "-" (the summary's statistics are NaN, never printed).
  const char* f3 = "{:.3f}";
  t += fmt::format("  K_gamma (max L_i)            {}\n", Figure(sum.k_gamma, "{:.6f}", "-"));
  t += fmt::format("  dynamic transmission error   {} .. {} urad (peak to peak {} urad)\n",
                   Figure(sum.te_min * 1e6, f3, "-"), Figure(sum.te_max * 1e6, f3, "-"),
                   Figure(sum.te_peak_to_peak() * 1e6, f3, "-"));
  t += fmt::format("  sun orbit radius             {} um largest, {} um mean\n",
                   Figure(sum.orbit_radius * 1e6, f3, "-"),
                   Figure(sum.orbit_mean_radius * 1e6, f3, "-"));
  t += fmt::format(
      "  integration                  {} steps, {} evaluations ({} for FD Jacobians), {} "
      "Jacobians, {} failed contact solves, {} error-test failures, {} nonlinear failures, {:.3f} "
      "s wall ({:.3f} s in evaluations)\n",
      st.steps, st.rhs_evaluations, st.fd_rhs_evaluations, st.jacobian_evaluations,
      st.failed_solves, st.error_test_failures, st.nonlinear_failures, st.wall_seconds,
      st.rhs_seconds);
  return t + RootStressText(sum.root_stress, "t s", 1.0);
}

MeshStiffnessFile::MeshStiffnessFile(const std::string& path, const nlohmann::json& provenance,
                                     double face_width,
                                     const std::vector<std::string>& stress_gears, int slices)
    : csv_(path),
      face_width_(face_width),
      bodies_(static_cast<int>(stress_gears.size())),
      faces_(slices > 1) {
  csv_.Write(ProvenanceCsvLine(provenance) +
             "angle_deg,converged,mesh_stiffness_N_per_m,mesh_stiffness_N_per_mm_um,"
             "transmission_error_urad,approach_um,total_force_N,pairs,"
             "pair_teeth,pair_kind,pair_force_N,pair_stiffness_N_per_m,pair_share,message" +
             RootStressHead(stress_gears, true) + (faces_ ? ",K_Hbeta,largest_z_mm" : "") + "\n");
}

void MeshStiffnessFile::Write(const transmission::MeshSample& s) {
  const std::string head =
      fmt::format("{:.6f},{},{},{},{},{},{},{}", geometry::Deg(s.angle), s.converged ? 1 : 0,
                  Cell(s.mesh_stiffness), Cell(s.mesh_stiffness / face_width_ / 1e9),
                  Cell(s.rotation * 1e6), Cell(s.approach * 1e6), Cell(s.total_force), s.pairs.size());
  std::string tail = CsvText(s.message);
  // A failed position has no stresses (empty cells), a converged one its extremes per gear.
  if (bodies_ > 0) RootStressCells(tail, s.root_stress, bodies_, true);
  if (faces_) {
    // A failed position (no line loads) has empty cells.
    const bool has = s.converged && !s.face_load.line_load.empty();
    CommaCell(tail, has ? s.face_load.k_h_beta : kNaN);
    CommaCell(tail, has ? s.face_load.largest_z * 1e3 : kNaN);
  }
  tail += '\n';
  std::string lines = s.pairs.empty() ? head + ",,,,,," + tail : "";
  for (const auto& p : s.pairs)
    lines += fmt::format("{},{}/{},{},{},{},{},{}", head, p.tooth1, p.tooth2,
                         CsvText(geometry::KindName(p.kind)), Cell(p.force), Cell(p.stiffness),
                         Cell(p.share), tail);
  csv_.Write(lines);
}

void MeshStiffnessFile::Close() { csv_.Close(); }

std::string MeshStiffnessText(const transmission::StiffnessRecord& record) {
  const transmission::MeshStiffnessResult& result = record.result;
  const double c_prime = record.iso6336_c_prime, c_gamma_alpha = record.iso6336_c_gamma_alpha;
  const auto positions = result.samples.size();
  std::string out;
  if (result.failed >= static_cast<int>(positions)) {
    out += "\n  no position converged: no mesh stiffness\n";
  } else {
    const double mean = result.mean_per_width(), peak = result.peak_pair_per_width();
    out += fmt::format(
        "\n  mean mesh stiffness      {:10.4g} N/m = {:6.2f} N/(mm um)   ISO 6336-1 c_gamma_alpha "
        "{:6.2f} (ratio {:.3f})\n",
        result.mean_stiffness, mean, c_gamma_alpha, mean / c_gamma_alpha);
    if (!result.helical) {
      out += fmt::format(
          "  peak single-pair         {:10.4g} N/m = {:6.2f} N/(mm um)   ISO 6336-1 c'            "
          "{:6.2f} (ratio {:.3f})\n",
          result.peak_pair_stiffness, peak, c_prime, peak / c_prime);
    } else {
      // A helical tooth pair never carries the mesh alone across the face: ISO's c′ stands for
      // one section's single pair (docs/mesh_stiffness.md, "Helical pairs").
      const double single = result.peak_slice_pair_per_width();
      out += fmt::format(
          "  peak tooth pair          {:10.4g} N/m = {:6.2f} N/(mm um) over the face; beta {:.4g} "
          "deg, overlap ratio {:.4f}\n",
          result.peak_pair_stiffness, peak, geometry::Deg(record.helix_angle),
          record.overlap_ratio);
      out += fmt::format(
          "  single pair, one section                  {:6.2f} N/(mm um)   ISO 6336-1 c'           "
          " "
          "{:6.2f} (ratio {:.3f})\n",
          single, c_prime, single / c_prime);
    }
    out += fmt::format(
        "  mesh stiffness range     {:10.4g} .. {:.4g} N/m; contact ratio {:.4f} (tip circles)\n",
        result.min_stiffness, result.max_stiffness, record.contact_ratio);
  }
  if (result.slices > 1)
    out += fmt::format(
        "  K_Hbeta ({} slices)      max {} at {} deg (largest load at z = {} mm), mean {}\n",
        result.slices, Figure(result.k_h_beta_max, "{:.6f}", "-"),
        Figure(geometry::Deg(result.k_h_beta_angle), "{:.4f}", "-"),
        Figure(result.largest_z * 1e3, "{:.3f}", "-"), Figure(result.k_h_beta_mean, "{:.6f}", "-"));
  out += fmt::format("  positions failed         {} of {}\n", result.failed, positions);
  return out + RootStressText(result.root_stress, "angle deg", geometry::Deg(1.0));
}

void WriteMeshStiffnessPlot(const std::string& path, const std::string& title,
                            const transmission::MeshStiffnessResult& result, double face_width,
                            std::vector<double> references) {
  const double b = face_width;
  LinePlot plot;
  plot.title = title;
  plot.x_label = "gear 1 rotation [deg]";
  plot.y_label = "stiffness per face width [N/(mm um)]";
  PlotSeries mesh{"mesh", {}, {}};
  std::map<std::string, PlotSeries> pairs;
  for (const auto& s : result.samples) {
    if (!s.converged) continue;
    mesh.x.push_back(geometry::Deg(s.angle));
    mesh.y.push_back(s.mesh_stiffness / b / 1e9);
    for (const auto& p : s.pairs) {
      PlotSeries& ser = pairs[fmt::format("pair {}/{}", p.tooth1, p.tooth2)];
      ser.name = fmt::format("pair {}/{}", p.tooth1, p.tooth2);
      ser.points = true;
      ser.x.push_back(geometry::Deg(s.angle));
      ser.y.push_back(p.stiffness / b / 1e9);
    }
  }
  plot.series.push_back(mesh);
  for (auto& [k, s] : pairs) plot.series.push_back(s);
  plot.y_references = std::move(references);
  WriteTextFile(path, RenderSvg(plot));
}

}  // namespace epicycle::report
