#include "epicycle/compliance/influence_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <ctime>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/io/number_format.hpp"
#include "payload_io.hpp"

namespace epicycle::compliance {
namespace {

constexpr double kPi = 3.14159265358979323846;

double Cpu() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

Eigen::Matrix2d Rot(double angle) { return Eigen::Rotation2Dd(angle).toRotationMatrix(); }

// The fillet read-out of one side of one tooth: its points ordered from the space centre line to
// the form point (arc length s along the σ = +1 profile of tooth 0 after undoing the tooth's
// rotation and, for σ = −1, the mirror), each the average of the surface-stress functionals of
// the edges that share the node.
struct FilletReadout {
  std::vector<double> arc_length;  // [m]
  std::vector<int> node;
  std::vector<std::vector<std::pair<int, double>>> functional;  // (dof, Pa/m)
};

FilletReadout ReadFillet(const LinearElasticModel& model, const ProfilePath& path, double s_form,
                         double tooth_angle, bool mirrored, const std::string& set) {
  const std::vector<BoundaryEdge>& edges = model.mesh().EdgeSet(set);
  const Eigen::Matrix2d back = Eigen::Rotation2Dd(-tooth_angle).toRotationMatrix();
  struct Entry {
    double s = 0.0;
    int node = -1;
    std::vector<std::pair<int, double>> sum;
    int count = 0;
  };
  std::vector<Entry> entries;
  for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
    for (int a = 0; a < 3; ++a) {
      const int node = edges[static_cast<std::size_t>(e)].nodes[static_cast<std::size_t>(a)];
      auto it = std::find_if(entries.begin(), entries.end(),
                             [&](const Entry& x) { return x.node == node; });
      if (it == entries.end()) {
        Eigen::Vector2d q = back * model.mesh().nodes[static_cast<std::size_t>(node)];
        if (mirrored) q.y() = -q.y();
        entries.push_back({path.Project(q, 0.0, s_form), node, {}, 0});
        it = entries.end() - 1;
      }
      for (const auto& term : model.SurfaceStressFunctional(set, EdgePoint{e, a - 1.0}))
        it->sum.push_back(term);
      ++it->count;
    }
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& x, const Entry& y) { return x.s < y.s; });
  FilletReadout out;
  for (Entry& x : entries) {
    for (auto& term : x.sum) term.second /= x.count;
    out.arc_length.push_back(x.s);
    out.node.push_back(x.node);
    out.functional.push_back(std::move(x.sum));
  }
  return out;
}

using io::Num;

int FlankIndex(int flank, const char* what) {
  if (flank != 1 && flank != -1) {
    throw std::invalid_argument(std::string("InfluenceTable: ") + what +
                                ".flank = " + std::to_string(flank) + ": must be +1 or -1");
  }
  return flank == 1 ? 0 : 1;
}

}  // namespace

void InfluenceTableOptions::Validate() const {
  mesh.Validate();
  if (!std::isfinite(join_depth) || join_depth < 0.0) {
    throw std::invalid_argument("InfluenceTableOptions.join_depth = " + Num(join_depth) +
                                " m: must be finite and >= 0 (0 selects the default)");
  }
  if (!std::isfinite(join_depth_factor) || join_depth_factor <= 0.0) {
    throw std::invalid_argument("InfluenceTableOptions.join_depth_factor = " +
                                Num(join_depth_factor) + ": must be finite and > 0");
  }
  if (batch < 1 || batch > 4096) {
    throw std::invalid_argument("InfluenceTableOptions.batch = " + std::to_string(batch) +
                                ": must be in [1, 4096]");
  }
}

std::size_t InfluenceTable::FilletIndex(int fl, int i, int c, int k, int f) const {
  const std::size_t m = fillet_.size();
  return ((((static_cast<std::size_t>(fl) * n_ + i) * 2 + c) * teeth_ + k) * 2 + f) * m;
}

InfluenceTable::FilletLoad InfluenceTable::PrepareFilletLoad(const DirectedNode& load,
                                                             double force) const {
  if (!has_fillet_stress())
    throw std::logic_error("InfluenceTable: built without fillet stress (fillet_stress = false)");
  FilletLoad out;
  out.tooth = load.tooth;
  // The row of (grid point first + p, axis c) is 2p + c rows of all fillets after the first's.
  const double* first = &fillet_stress_[FilletIndex(load.flank_index, load.node.first, 0, 0, 0)];
  const std::size_t rows = FilletIndex(0, 0, 1, 0, 0);
  for (int p = 0; p < 4; ++p) {
    for (int c = 0; c < 2; ++c) {
      const auto pc = static_cast<std::size_t>(2 * p + c);
      const double w = force * load.load_weight[pc];
      if (w == 0.0) continue;
      const auto q = static_cast<std::size_t>(out.count++);
      out.weight[q] = w;
      out.row[q] = first + pc * rows;
    }
  }
  return out;
}

void InfluenceTable::AddFilletStress(const FilletLoad& load, int tooth, int side,
                                     double* sigma) const {
  const FilletTarget target{tooth, side, sigma};
  AddFilletStress(load, std::span<const FilletTarget>(&target, 1));
}

void InfluenceTable::AddFilletStress(const FilletLoad& load,
                                     std::span<const FilletTarget> fillets) const {
  const int z = teeth_;
  const std::size_t m_count = fillet_.size();
  // Per fillet its rows: the fixed offset of (response tooth seen from the load's, side).
  auto offset = [&](const FilletTarget& f) {
    if (f.side != 0 && f.side != 1)
      throw std::invalid_argument("InfluenceTable: fillet side " + std::to_string(f.side) +
                                  ": must be 0 (sigma = +1) or 1 (sigma = -1)");
    const int k = ((f.tooth - load.tooth) % z + z) % z;
    return (static_cast<std::size_t>(k) * 2 + static_cast<std::size_t>(f.side)) * m_count;
  };
  // Per point the weights in the order AddFilletStress(DirectedNode) adds them: the same
  // roundings, one load and store of σ. The weights are copied to locals (σ's stores cannot alias
  // them): they stay in registers over the fillets and their points.
  const std::array<double, 8> w = load.weight;
  if (load.count != 8) {
    for (const FilletTarget& f : fillets) {
      const std::size_t o = offset(f);
      double* __restrict out = f.sigma;
      for (std::size_t m = 0; m < m_count; ++m) {
        double s = out[m];
        for (std::size_t q = 0; q < static_cast<std::size_t>(load.count); ++q)
          s += w[q] * load.row[q][o + m];
        out[m] = s;
      }
    }
    return;
  }
  // The usual load (8 non-zero weights): two points at a time as one SSE2 packet (an Eigen
  // expression of fixed size 2, evaluated element by element in that order), then the last odd
  // point.
  using Pair = Eigen::Array2d;
  using Row = Eigen::Map<const Pair>;
  for (const FilletTarget& f : fillets) {
    const std::size_t o = offset(f);
    std::array<const double*, 8> r{};
    for (std::size_t q = 0; q < 8; ++q) r[q] = load.row[q] + o;
    double* __restrict out = f.sigma;
    std::size_t m = 0;
    for (; m + 2 <= m_count; m += 2) {
      Eigen::Map<Pair> s(out + m);
      s = s + w[0] * Row(r[0] + m) + w[1] * Row(r[1] + m) + w[2] * Row(r[2] + m) +
          w[3] * Row(r[3] + m) + w[4] * Row(r[4] + m) + w[5] * Row(r[5] + m) +
          w[6] * Row(r[6] + m) + w[7] * Row(r[7] + m);
    }
    for (; m < m_count; ++m)
      out[m] = out[m] + w[0] * r[0][m] + w[1] * r[1][m] + w[2] * r[2][m] + w[3] * r[3][m] +
               w[4] * r[4][m] + w[5] * r[5][m] + w[6] * r[6][m] + w[7] * r[7][m];
  }
}

void InfluenceTable::AddFilletStress(const DirectedNode& load, double force, int tooth, int side,
                                     double* sigma) const {
  AddFilletStress(PrepareFilletLoad(load, force), tooth, side, sigma);
}

double InfluenceTable::FilletGridValue(int fl, int i, int c, int k, int f, int m) const {
  if (!has_fillet_stress())
    throw std::logic_error("InfluenceTable: built without fillet stress (fillet_stress = false)");
  if (fl < 0 || fl > 1 || i < 0 || i >= n_ || c < 0 || c > 1 || k < 0 || k >= teeth_ || f < 0 ||
      f > 1 || m < 0 || m >= static_cast<int>(fillet_.size()))
    throw std::invalid_argument("InfluenceTable::FilletGridValue: index out of range");
  return fillet_stress_[FilletIndex(fl, i, c, k, f) + static_cast<std::size_t>(m)];
}

InfluenceTable InfluenceTable::Build(const geometry::Gear& gear, const ElasticMaterial& material,
                                     const InfluenceTableOptions& options) {
  options.Validate();
  material.Validate();
  const double t0 = Cpu();
  GearBodyMesh body = BuildGearMesh(gear, options.mesh);
  std::vector<InfluenceTable> tables =
      SolveLoads(gear, material, options, std::move(body), Cpu() - t0, {0}, true);
  return std::move(tables.front());
}

// The table's solve on a given body mesh, loads on each of `load_teeth` (Build: tooth 0 of the
// cyclic body; DamagedInfluence: the teeth near a crack). Table q holds the loads on tooth
// t = load_teeth[q] in the frame of that tooth (directions and displacements turned by R_tᵀ;
// response tooth k stored at k − t mod z), so that every accessor reads it as "tooth 0". With
// `cyclic` the table is symmetrised by the cyclic Maxwell–Betti pairs and may carry fillet
// stresses; without, it keeps the raw values (the caller symmetrises the pairs it holds).
namespace {

constexpr int kLayerSamples = InfluenceTable::kLayerSamples;

// The depth read-out points of one load tooth's grid (DisplacementAtDepth's construction: the edge
// point at the node, minus the depth times the edge's outward normal m), located once: at h (the
// join) and at kLayerSamples depths r_k, where the layer strain is measured; per flank fl.
struct DepthReadouts {
  std::array<std::vector<ElementPoint>, 2> depth_at;                             // [fl][i] at h
  std::array<std::array<std::vector<ElementPoint>, kLayerSamples>, 2> layer_at;  // [fl][k][i]
  std::array<std::vector<Eigen::Vector2d>, 2> edge_normal;                       // [fl][i] m
};

DepthReadouts LocateDepthReadouts(const LinearElasticModel& model,
                                  const std::array<std::vector<int>, 2>& grid_nodes, int n, int lt,
                                  double depth_h, const std::array<double, kLayerSamples>& r_k,
                                  const std::string& who) {
  DepthReadouts d;
  for (int fl = 0; fl < 2; ++fl) {
    const std::string set = "flank" + std::to_string(lt) + (fl == 0 ? "+" : "-");
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d x = model.mesh().nodes[grid_nodes[fl][i]];
      const EdgePoint ep = model.mesh().LocateOnEdgeSet(set, x);
      const Eigen::Vector2d m = model.mesh().EdgeNormal(set, ep);
      d.edge_normal[fl].push_back(m);
      for (int k = -1; k < kLayerSamples; ++k) {
        const double depth = k < 0 ? depth_h : r_k[k];
        std::vector<ElementPoint>& at = k < 0 ? d.depth_at[fl] : d.layer_at[fl][k];
        try {
          at.push_back(model.LocatePoint(model.mesh().EdgePosition(set, ep) - depth * m));
        } catch (const std::invalid_argument& e) {
          throw std::invalid_argument(who + "the depth read-out of grid point " +
                                      std::to_string(i) + " at " + Num(depth * 1e3) +
                                      " mm is outside the body (" + e.what() + ")");
        }
      }
    }
  }
  return d;
}

// The fillet read-out of every side of every tooth (tooth 0's σ = +1 side defines the points;
// the cyclic, mirrored mesh gives every other side the same points, checked), [2 k + side].
std::vector<FilletReadout> ReadFillets(const LinearElasticModel& model, const ProfilePath& path,
                                       double form_arc, const geometry::Gear& gear, int z,
                                       const std::string& who) {
  std::vector<FilletReadout> fillets;
  const double tol = 1e-9 * gear.tip_radius();
  for (int k = 0; k < z; ++k) {
    for (int f = 0; f < 2; ++f) {
      const std::string set = "fillet" + std::to_string(k) + (f == 0 ? "+" : "-");
      fillets.push_back(ReadFillet(model, path, form_arc, k * gear.pitch_angle(), f == 1, set));
      const FilletReadout& r = fillets.back();
      const FilletReadout& r0 = fillets.front();
      bool same = r.arc_length.size() == r0.arc_length.size();
      for (std::size_t m = 0; same && m < r.arc_length.size(); ++m)
        same = std::abs(r.arc_length[m] - r0.arc_length[m]) <= tol;
      if (!same)
        throw std::invalid_argument(who + "the fillet points of set '" + set +
                                    "' are not those of tooth 0 (the mesh is not cyclic)");
    }
  }
  return fillets;
}

// The layer term per grid point [fl][i] [m/N] (docs/compliance.md, "The layer term"): the FE's
// normal approach less Flamant's, R(r) = D(r) + a ln r, is the structural (non-singular) field,
// which the half-plane local term does not contain. Its slope over [r1, r2] (least squares over
// the samples: the read-out inside an element carries an interpolation error that varies with the
// depth, which the fit averages), carried linearly to the surface, adds −h R' between the surface
// and h, so that the sum of the two terms no longer depends on h.
std::vector<double> LayerTerm(const std::vector<std::array<double, kLayerSamples>>& normal_at,
                              const std::array<double, kLayerSamples>& r_k, double flamant,
                              double depth_h, int n) {
  std::vector<double> layer(static_cast<std::size_t>(2) * n, 0.0);
  double mean_r = 0.0;
  for (double r : r_k) mean_r += r / kLayerSamples;
  for (std::size_t g = 0; g < layer.size(); ++g) {
    double mean_v = 0.0;
    for (int k = 0; k < kLayerSamples; ++k)
      mean_v += (normal_at[g][k] + flamant * std::log(r_k[k])) / kLayerSamples;
    double sxy = 0.0, sxx = 0.0;
    for (int k = 0; k < kLayerSamples; ++k) {
      const double dr = r_k[k] - mean_r;
      sxy += dr * (normal_at[g][k] + flamant * std::log(r_k[k]) - mean_v);
      sxx += dr * dr;
    }
    layer[g] = -depth_h * sxy / sxx;  // [m/N]
  }
  // Grid points alternate between corner and mid-side nodes of the Q8 edges, whose point loads
  // leave different errors one element deep: a (1, 2, 1)/4 filter along the flank removes that
  // alternation exactly and keeps linear trends (the structural field varies over the tooth's
  // thickness, many grid spacings).
  for (int fl = 0; fl < 2; ++fl) {
    const std::vector<double> c(layer.begin() + fl * n, layer.begin() + (fl + 1) * n);
    for (int i = 1; i + 1 < n; ++i)
      layer[static_cast<std::size_t>(fl) * n + i] = 0.25 * (c[i - 1] + 2.0 * c[i] + c[i + 1]);
  }
  return layer;
}

// Maxwell–Betti: Λ(a→b) = Λ(b→a)ᵀ. For a = (tooth 0, fl, i), b = (tooth k, fr, j), the
// reciprocal load sits on tooth k: Λ(b→a) = R_k M R_kᵀ with M = Λ((0, fr, j) → (−k, fl, i)).
// Returns the symmetrised table (the raw one for a body that is not cyclic) and the largest
// relative asymmetries of the raw table and of its self blocks; `index` is the table's Index.
template <class IndexOf>
std::vector<double> Symmetrise(const std::vector<double>& raw,
                               const std::vector<Eigen::Matrix2d>& self, int n, int z,
                               const geometry::Gear& gear, bool cyclic, const IndexOf& index,
                               double* asym_out, double* self_asym_out) {
  std::vector<double> sym(raw.size(), 0.0);
  auto block = [&](const std::vector<double>& v, int fl, int i, int k, int fr, int j) {
    Eigen::Matrix2d m;
    for (int c = 0; c < 2; ++c) {
      const std::size_t at = index(fl, i, c, k, fr, j);
      m(0, c) = v[at];
      m(1, c) = v[at + 1];
    }
    return m;
  };
  auto norm = [](const Eigen::Matrix2d& m) { return m.cwiseAbs().maxCoeff(); };
  double asym = 0.0, self_asym = 0.0;
  if (!cyclic) sym = raw;
  for (int fl = 0; fl < 2; ++fl) {
    for (int i = 0; i < n; ++i) {
      const Eigen::Matrix2d& s = self[static_cast<std::size_t>(fl) * n + i];
      self_asym = std::max(self_asym, std::abs(s(0, 1) - s(1, 0)) / norm(s));
    }
  }
  for (int fl = 0; fl < 2 && cyclic; ++fl) {
    for (int i = 0; i < n; ++i) {
      const double da = norm(self[static_cast<std::size_t>(fl) * n + i]);
      for (int k = 0; k < z; ++k) {
        const Eigen::Matrix2d r = Rot(k * gear.pitch_angle());
        const int back = (z - k) % z;
        for (int fr = 0; fr < 2; ++fr) {
          for (int j = 0; j < n; ++j) {
            const Eigen::Matrix2d ab = block(raw, fl, i, k, fr, j);
            const Eigen::Matrix2d ba_t =
                r * block(raw, fr, j, back, fl, i).transpose() * r.transpose();
            const double db = norm(self[static_cast<std::size_t>(fr) * n + j]);
            asym = std::max(asym, norm(ab - ba_t) / std::sqrt(da * db));
            const Eigen::Matrix2d avg = 0.5 * (ab + ba_t);
            for (int c = 0; c < 2; ++c) {
              const std::size_t at = index(fl, i, c, k, fr, j);
              sym[at] = avg(0, c);
              sym[at + 1] = avg(1, c);
            }
          }
        }
      }
    }
  }
  *asym_out = asym;
  *self_asym_out = self_asym;
  return sym;
}

}  // namespace

std::vector<InfluenceTable> InfluenceTable::SolveLoads(const geometry::Gear& gear,
                                                       const ElasticMaterial& material,
                                                       const InfluenceTableOptions& options,
                                                       GearBodyMesh body, double t_mesh_before,
                                                       const std::vector<int>& load_teeth,
                                                       bool cyclic) {
  const std::string who = "influence table of '" + gear.name() + "': ";
  if (!cyclic && options.fillet_stress)
    throw std::invalid_argument(who + "fillet stresses are tabulated for a cyclic body only");
  InfluenceTable t;
  t.gear_ = std::make_shared<const geometry::Gear>(gear);
  t.path_ = std::make_shared<const ProfilePath>(*t.gear_);
  t.module_ = gear.module();

  double t0 = Cpu();
  t.teeth_ = body.teeth;
  t.grid_ = body.grid;
  t.n_ = body.grid.num_points();
  t.BuildDerived();
  const int n = t.n_, z = t.teeth_;

  // Join depth: admissible below the distance to the tooth centre line along the normal.
  t.max_depth_ = std::numeric_limits<double>::infinity();
  int limiting = 0;
  for (int i = 0; i < n; ++i) {
    const double ny = t.grid_.normal[i].y();
    const double d =
        ny > 0.0 ? t.grid_.position[i].y() / ny : std::numeric_limits<double>::infinity();
    if (d < t.max_depth_) {
      t.max_depth_ = d;
      limiting = i;
    }
  }
  t.depth_ = options.join_depth > 0.0
                 ? options.join_depth
                 : options.join_depth_factor * kDefaultDepthFraction * t.max_depth_;
  if (!(t.depth_ < t.max_depth_)) {
    std::ostringstream msg;
    msg << who << "join_depth h = " << t.depth_ * 1e3 << " mm reaches past the tooth centre line: "
        << "from flank-grid point " << limiting << " (s = " << t.grid_.arc_length[limiting] * 1e3
        << " mm) the centre line is " << t.max_depth_ * 1e3
        << " mm away along the normal; the rule is h < that distance (default h = "
        << kDefaultDepthFraction << " of it)";
    throw std::invalid_argument(msg.str());
  }
  const double t_mesh = t_mesh_before + Cpu() - t0;

  t0 = Cpu();
  LinearElasticModel model(std::move(body.mesh), material);
  t.num_dofs_ = model.num_dofs();
  t.num_elements_ = model.mesh().num_elements();
  model.FixNodeSet("hub");
  model.Factorize();
  const double t_factor = Cpu() - t0;

  std::vector<InfluenceTable> result;
  for (const int load_tooth : load_teeth) {
    t0 = Cpu();
    const int lt = ((load_tooth % z) + z) % z;
    // R_tᵀ of the load tooth (identity for tooth 0, whose values are then those of Build).
    const Eigen::Matrix2d to_load = Rot(-lt * gear.pitch_angle());
    auto local = [&](const Eigen::Vector2d& v) -> Eigen::Vector2d {
      return lt == 0 ? v : Eigen::Vector2d(to_load * v);
    };
    // Depth read-out points of tooth 0's grid: at h and at kLayerSamples depths r_k evenly over
    // [r1, r2], where the layer strain is measured.
    const double r1 = kDefaultDepthFraction * t.max_depth_, r2 = kLayerDepthRatio * r1;
    std::array<double, kLayerSamples> r_k;
    for (int k = 0; k < kLayerSamples; ++k) r_k[k] = r1 + (r2 - r1) * k / (kLayerSamples - 1);
    const DepthReadouts readouts =
        LocateDepthReadouts(model, body.grid_nodes[lt], n, lt, t.depth_, r_k, who);
    const auto& depth_at = readouts.depth_at;
    const auto& layer_at = readouts.layer_at;
    const auto& edge_normal = readouts.edge_normal;
    // Flamant's coefficient a = 2k/(π b) (k = (1−ν²)/E plane strain, 1/E plane stress): the
    // half-plane's normal approach between depths r1 and r2 under a unit point load is a ln(r2/r1).
    const ElasticMaterial& mat = model.material();
    const double flamant = 2.0 *
                           (mat.plane == PlaneAssumption::kPlaneStrain
                                ? (1.0 - mat.poisson_ratio * mat.poisson_ratio) / mat.youngs_modulus
                                : 1.0 / mat.youngs_modulus) /
                           (kPi * mat.thickness);
    const std::size_t total = static_cast<std::size_t>(2) * n * 2 * z * 2 * n * 2;
    std::vector<double> raw(total, 0.0);
    std::vector<Eigen::Matrix2d> self(static_cast<std::size_t>(2) * n, Eigen::Matrix2d::Zero());
    // Normal approach mᵀ U m at the layer depths per grid point (the sum over the two load cases).
    std::vector<std::array<double, kLayerSamples>> normal_at(static_cast<std::size_t>(2) * n);
    for (auto& v : normal_at) v.fill(0.0);
    // The fillet read-out of every side of every tooth (tooth 0's σ = +1 side defines the points;
    // the cyclic, mirrored mesh gives every other side the same points, checked).
    std::vector<FilletReadout> fillets;
    if (options.fillet_stress) {
      fillets = ReadFillets(model, *t.path_, t.grid_.form_arc, gear, z, who);
      for (std::size_t m = 0; m < fillets.front().arc_length.size(); ++m) {
        const double sm = fillets.front().arc_length[m];
        t.fillet_.push_back({sm,
                             model.mesh().nodes[static_cast<std::size_t>(fillets.front().node[m])],
                             t.path_->Tangent(sm)});
      }
      t.fillet_stress_.assign(static_cast<std::size_t>(2) * n * 2 * z * 2 * t.fillet_.size(), 0.0);
    }
    const int cases = 2 * n * 2;
    for (int first = 0; first < cases; first += options.batch) {
      const int count = std::min(options.batch, cases - first);
      Eigen::MatrixXd f = Eigen::MatrixXd::Zero(model.num_dofs(), count);
      for (int q = 0; q < count; ++q) {
        const int id = first + q, c = id % 2, i = (id / 2) % n, fl = id / (2 * n);
        const int node = body.grid_nodes[lt][fl][i];
        if (lt == 0) {
          f(LinearElasticModel::Dof(node, c), q) = 1.0;
        } else {  // unit force along the load tooth's axis c, R_t e_c
          f(LinearElasticModel::Dof(node, 0), q) = to_load(c, 0);
          f(LinearElasticModel::Dof(node, 1), q) = to_load(c, 1);
        }
      }
      const Eigen::MatrixXd u = model.SolveMany(f);
      for (int q = 0; q < count; ++q) {
        const int id = first + q, c = id % 2, i = (id / 2) % n, fl = id / (2 * n);
        for (int k = 0; k < z; ++k) {
          const int dk = ((k - lt) % z + z) % z;
          for (int fr = 0; fr < 2; ++fr) {
            for (int j = 0; j < n; ++j) {
              const int node = body.grid_nodes[k][fr][j];
              const std::size_t at = t.Index(fl, i, c, dk, fr, j);
              const Eigen::Vector2d v = local(Eigen::Vector2d(u(2 * node, q), u(2 * node + 1, q)));
              raw[at] = v.x();
              raw[at + 1] = v.y();
            }
          }
        }
        for (int k = 0; k < z && options.fillet_stress; ++k) {
          for (int side = 0; side < 2; ++side) {
            const FilletReadout& r = fillets[static_cast<std::size_t>(2 * k + side)];
            double* out = &t.fillet_stress_[t.FilletIndex(fl, i, c, k, side)];
            for (std::size_t m = 0; m < r.functional.size(); ++m) {
              double sigma = 0.0;
              for (const auto& [dof, coefficient] : r.functional[m])
                sigma += coefficient * u(dof, q);
              out[m] = sigma;
            }
          }
        }
        const std::size_t g = static_cast<std::size_t>(fl) * n + i;
        self[g].col(c) = local(model.Displacement(u.col(q), depth_at[fl][i]));
        const Eigen::Vector2d& m = edge_normal[fl][i];
        const Eigen::Vector2d ml = local(m);
        for (int k = 0; k < kLayerSamples; ++k)
          normal_at[g][k] += ml(c) * m.dot(model.Displacement(u.col(q), layer_at[fl][k][i]));
      }
    }
    // The layer term (docs/compliance.md, "The layer term").
    std::vector<double> layer(static_cast<std::size_t>(2) * n, 0.0);
    if (options.layer_term) layer = LayerTerm(normal_at, r_k, flamant, t.depth_, n);

    // Maxwell–Betti symmetry.
    double asym = 0.0, self_asym = 0.0;
    std::vector<double> sym = Symmetrise(
        raw, self, n, z, gear, cyclic,
        [&t](int fl, int i, int c, int k, int fr, int j) { return t.Index(fl, i, c, k, fr, j); },
        &asym, &self_asym);
    for (auto& s : self) s = 0.5 * (s + s.transpose()).eval();
    for (int fl = 0; fl < 2; ++fl) {
      for (int i = 0; i < n; ++i) {
        const std::size_t g = static_cast<std::size_t>(fl) * n + i;
        const Eigen::Vector2d ml = local(edge_normal[fl][i]);
        self[g] += layer[g] * ml * ml.transpose();
      }
    }
    // The join: the loaded point's own entry is the depth-h read-out.
    for (int fl = 0; fl < 2; ++fl) {
      for (int i = 0; i < n; ++i) {
        const Eigen::Matrix2d& s = self[static_cast<std::size_t>(fl) * n + i];
        for (int c = 0; c < 2; ++c) {
          const std::size_t at = t.Index(fl, i, c, 0, fl, i);
          sym[at] = s(0, c);
          sym[at + 1] = s(1, c);
        }
      }
    }
    InfluenceTable& r = result.emplace_back(t);
    r.raw_asymmetry_ = asym;
    r.raw_self_asymmetry_ = self_asym;
    r.surface_ = std::move(sym);
    r.self_ = std::move(self);
    r.layer_ = std::move(layer);
    r.raw_ = std::move(raw);
    r.seconds_ = {t_mesh, t_factor, Cpu() - t0};
  }
  return result;
}

void InfluenceTable::CheckHalfWidth(double half_width) const {
  if (!(std::isfinite(half_width) && half_width >= 0.0) ||
      !(depth_ >= kMinDepthOverHalfWidth * half_width)) {
    std::ostringstream msg;
    msg << "influence table of '" << gear_->name() << "': join depth h = " << depth_ * 1e3
        << " mm against the Hertz half-width L = " << half_width * 1e3
        << " mm: the rule is h >= " << kMinDepthOverHalfWidth
        << " L (h well above L); lower the load or raise join_depth (at most " << max_depth_ * 1e3
        << " mm here)";
    throw std::invalid_argument(msg.str());
  }
}

// Piecewise cubic Hermite in arc length, nodal slopes from the parabola through three points:
// f'_m ≈ Σ_t K_m,t f_(m0+t), m0 = clamp(m − 1, 0, n − 3) (one-sided at the ends), K from the grid
// alone (slope_, formed once by BuildDerived).
void InfluenceTable::Weights(double s, int* first, std::array<double, 4>* w) const {
  const std::vector<double>& g = grid_.arc_length;
  const int n = n_;
  const double tol = 1e-9 * g.back();
  if (!(s >= -tol && s <= g.back() + tol)) {
    std::ostringstream msg;
    msg << "InfluenceTable: arc length s = " << s * 1e3 << " mm is outside the flank grid [0, "
        << g.back() * 1e3 << "] mm (form point to tip-round end)";
    throw std::invalid_argument(msg.str());
  }
  s = std::clamp(s, 0.0, g.back());
  // The interval: the last grid point at or below s (upper_bound's answer less one), walked to
  // from the interval a uniform grid would give; on the increasing grid the walk ends where the
  // bisection does, in a step or two (the grid is nearly uniform in arc length).
  int i = std::clamp(static_cast<int>(s * interval_scale_), 0, n - 1);
  while (i > 0 && g[i] > s) --i;
  while (i + 1 < n && g[i + 1] <= s) ++i;
  i = std::clamp(i, 0, n - 2);
  const int lo = std::clamp(i - 1, 0, n - 4);
  *first = lo;
  w->fill(0.0);
  // Adds coef · f'_m's weights.
  auto slope = [&](int m, double coef) {
    const int m0 = std::clamp(m - 1, 0, n - 3);
    const std::array<double, 3>& k = slope_[static_cast<std::size_t>(m)];
    for (int t = 0; t < 3; ++t) (*w)[m0 + t - lo] += coef * k[t];
  };
  const double d = g[i + 1] - g[i];
  const double x = (s - g[i]) / d;
  const double h00 = (1 + 2 * x) * (1 - x) * (1 - x), h10 = x * (1 - x) * (1 - x);
  const double h01 = x * x * (3 - 2 * x), h11 = x * x * (x - 1);
  (*w)[i - lo] += h00;
  (*w)[i + 1 - lo] += h01;
  slope(i, d * h10);
  slope(i + 1, d * h11);
}

InfluenceTable::Node InfluenceTable::Prepare(const FlankPosition& position) const {
  FlankIndex(position.flank, "position");
  Node node;
  node.position = position;
  Weights(position.arc_length, &node.first, &node.weight);
  return node;
}

Eigen::Matrix2d InfluenceTable::Influence(const FlankPosition& load,
                                          const FlankPosition& response) const {
  FlankIndex(load.flank, "load");
  FlankIndex(response.flank, "response");
  return PreparedInfluence(Prepare(load), Prepare(response));
}

Eigen::Matrix2d InfluenceTable::PreparedInfluence(const Node& load_node,
                                                  const Node& response_node) const {
  const FlankPosition& load = load_node.position;
  const FlankPosition& response = response_node.position;
  const int fl = load.flank > 0 ? 0 : 1;
  const int fr = response.flank > 0 ? 0 : 1;
  const int z = teeth_;
  const int k1 = ((load.tooth % z) + z) % z, k2 = ((response.tooth % z) + z) % z;
  const int dk = ((k2 - k1) % z + z) % z;
  const Eigen::Matrix2d& r = tooth_rotation_[static_cast<std::size_t>(k1)];
  const int a0 = load_node.first, b0 = response_node.first;
  const std::array<double, 4>& wa = load_node.weight;
  const std::array<double, 4>& wb = response_node.weight;
  Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
  const bool self = dk == 0 && fl == fr &&
                    std::abs(load.arc_length - response.arc_length) <= 1e-12 * arc_length_max();
  if (self) {
    for (int p = 0; p < 4; ++p) m += wa[p] * self_[static_cast<std::size_t>(fl) * n_ + a0 + p];
  } else {
    // Index(fl, i, c, dk, fr, j) steps by 2 in j: the response stencil is one contiguous run.
    const std::size_t run = Index(0, 0, 0, dk, fr, b0);
    for (int p = 0; p < 4; ++p) {
      if (wa[p] == 0.0) continue;
      for (int c = 0; c < 2; ++c) {
        const double* row = surface_.data() + Index(fl, a0 + p, c, 0, 0, 0) + run;
        double x = 0.0, y = 0.0;
        for (int q = 0; q < 4; ++q) {
          x += wb[q] * row[2 * q];
          y += wb[q] * row[2 * q + 1];
        }
        m(0, c) += wa[p] * x;
        m(1, c) += wa[p] * y;
      }
    }
  }
  return r * m * r.transpose();
}

InfluenceTable::DirectedNode InfluenceTable::PrepareDirected(
    const FlankPosition& position, const Eigen::Vector2d& direction) const {
  DirectedNode d;
  d.node = Prepare(position);
  d.direction = direction;
  const int z = teeth_;
  d.tooth = ((position.tooth % z) + z) % z;
  d.flank_index = position.flank > 0 ? 0 : 1;
  const Eigen::Vector2d v =
      tooth_rotation_[static_cast<std::size_t>(d.tooth)].transpose() * direction;
  for (int p = 0; p < 4; ++p) {
    d.load_weight[2 * p] = d.node.weight[p] * v.x();
    d.load_weight[2 * p + 1] = d.node.weight[p] * v.y();
  }
  return d;
}

// With the load on tooth k1 and the response on tooth k2 = k1 + Δk (mod z), the class comment's
// cyclic symmetry gives Λ = R_k1 Λ0 R_k1ᵀ, where Λ0 (load on tooth 0, response on tooth Δk) is the
// tensor-product interpolant Λ0 = Σ_p Σ_q w_p w'_q T(a0 + p → b0 + q), w and w' the load's and the
// response's stencil weights and T(i → j) the 2×2 table block (column c: load along axis c,
// row e: displacement component e). So
//   d_rᵀ Λ d_l = uᵀ Λ0 v = Σ_{p,c} (w_p v_c) Σ_{q,e} (w'_q u_e) T_ec(a0 + p → b0 + q),
// u = R_k1ᵀ d_r and v = R_k1ᵀ d_l (the load's load_weight holds w_p v_c). T_ec(i → j) is stored at
// Index(fl, i, c, Δk, fr, j) + e: for fixed (fl, Δk, fr) the eight rows ρ = 2p + c start at
// Index(fl, a0, 0, Δk, fr, b0) + ρ P (P = 4 z n values per unit load: Index steps by P in c and
// by 2P in i) and each row holds the response stencil's values [x_q, y_q], q = 0 … 3, in a run.
// The sum is taken as a_i = Σ_ρ (w_p v_c)_ρ row_ρ[i] (i = 2q + e), then Σ_q w'_q (u_x a_2q +
// u_y a_2q+1): 64 multiply-adds and no 2×2 products. The self term (the same position) reads the
// depth-h blocks S_p instead: uᵀ Λ0 v = Σ_{p,c} (w_p v_c) (uᵀ S_p)_c.
double InfluenceTable::DirectedCompliance(const DirectedNode& load,
                                          const DirectedNode& response) const {
  const int fl = load.flank_index, fr = response.flank_index;
  int dk = response.tooth - load.tooth;
  if (dk < 0) dk += teeth_;
  const Eigen::Vector2d u =
      tooth_rotation_[static_cast<std::size_t>(load.tooth)].transpose() * response.direction;
  const std::array<double, 8>& alpha = load.load_weight;
  const bool self = dk == 0 && fl == fr &&
                    std::abs(load.node.position.arc_length - response.node.position.arc_length) <=
                        1e-12 * arc_length_max();
  if (self) {
    const Eigen::Matrix2d* s = self_.data() + static_cast<std::size_t>(fl) * n_ + load.node.first;
    double sum = 0.0;
    for (int p = 0; p < 4; ++p) {
      sum += alpha[2 * p] * (u.x() * s[p](0, 0) + u.y() * s[p](1, 0)) +
             alpha[2 * p + 1] * (u.x() * s[p](0, 1) + u.y() * s[p](1, 1));
    }
    return sum;
  }
  const std::size_t stride = static_cast<std::size_t>(teeth_) * 4 * n_;  // P
  const double* base = surface_.data() + Index(fl, load.node.first, 0, dk, fr, response.node.first);
  // Eight-element rows: Eigen's packets vectorise the update along a row (the order of each a_i's
  // sum is kept).
  using Row = Eigen::Matrix<double, 8, 1>;
  Row a = alpha[0] * Eigen::Map<const Row>(base);
  for (int r = 1; r < 8; ++r) a.noalias() += alpha[r] * Eigen::Map<const Row>(base + r * stride);
  const std::array<double, 4>& w = response.node.weight;
  double sum = 0.0;
  for (int q = 0; q < 4; ++q) sum += w[q] * (u.x() * a[2 * q] + u.y() * a[2 * q + 1]);
  return sum;
}

bool InfluenceTable::TryLocate(const Eigen::Vector2d& point, int tooth, int flank,
                               FlankPosition* out, double* distance_out) const {
  const int z = teeth_;
  const int k = ((tooth % z) + z) % z;
  Eigen::Vector2d q = tooth_rotation_[static_cast<std::size_t>(k)].transpose() * point;
  if (flank == -1) q.y() = -q.y();
  const int last = static_cast<int>(dense_.size()) - 1;
  auto dist2 = [&](int p) { return (dense_[p].point - q).squaredNorm(); };
  // The nearest point of the dense polyline (kDense points per grid interval on the exact
  // profile). The profile's radius is monotonic from the form point to the tip-round end (rising
  // on an external tooth, falling on an internal one), so bisection on |q| starts next to it and
  // a descent along the polyline finds it; a point near the flat end of the tip round, where the
  // radius no longer tells positions apart, may start a few points off and the descent walks
  // there. A descent that ends more than a grid interval from its start, or at a point out of
  // tolerance, falls back to the scan of every point (never taken for points on the profile; kept
  // so that neither the answer nor a rejection ever depends on the shortcut).
  //
  // The bisection runs on the key ±|q| (the sign of the profile's direction, dense_key_ rising
  // along it): its first point with key ≥ ±|q|. A bucket of equal key width narrows its range to
  // the points between the bucket's edges; the range is used only if the point before it is below
  // the key and the point after it is not, which on the sorted keys makes the narrowed bisection
  // return exactly the whole one (BuildDerived leaves the buckets out if the keys are not sorted).
  const double key = key_sign_ * q.norm();
  int lo = 0, hi = last + 1;
  if (!bucket_.empty()) {
    const double x = (key - bucket_origin_) * bucket_scale_;
    const int buckets = static_cast<int>(bucket_.size()) - 1;
    const int b = x > 0.0 ? static_cast<int>(std::min(x, buckets - 1.0)) : 0;
    const int b_lo = bucket_[b], b_hi = bucket_[b + 1];
    if ((b_lo == 0 || dense_key_[b_lo - 1] < key) && (b_hi > last || !(dense_key_[b_hi] < key))) {
      lo = b_lo;
      hi = b_hi;
    }
  }
  const auto it = std::lower_bound(dense_key_.begin() + lo, dense_key_.begin() + hi, key);
  int m = std::clamp(static_cast<int>(it - dense_key_.begin()), 0, last);
  const int start = m;
  double best = dist2(m);
  for (int step : {-1, 1}) {
    while (m + step >= 0 && m + step <= last && dist2(m + step) < best) {
      m += step;
      best = dist2(m);
    }
  }
  auto scan_all = [&] {
    for (int p = 0; p <= last; ++p) {
      const double d = dist2(p);
      if (d < best) {
        best = d;
        m = p;
      }
    }
  };
  // The foot on the chords next to dense point m: the chord error is κΔ²/8 (Δ the dense
  // spacing), below 1e-8 m for these profiles.
  auto foot = [&](double* s, double* distance) {
    *s = dense_[m].arc_length;
    *distance = std::sqrt(best);
    for (int p : {m - 1, m}) {
      if (p < 0 || p >= last) continue;
      const Eigen::Vector2d a = dense_[p].point, e = dense_[p + 1].point - a;
      const double t = (q - a).dot(e) / e.squaredNorm();
      if (t < 0.0 || t > 1.0) continue;
      const double d = (a + t * e - q).norm();
      if (d < *distance) {
        *distance = d;
        *s = dense_[p].arc_length + t * (dense_[p + 1].arc_length - dense_[p].arc_length);
      }
    }
  };
  bool scanned = std::abs(m - start) > kDense;
  if (scanned) scan_all();
  double s = 0, distance = 0;
  foot(&s, &distance);
  const double tolerance = 1e-3 * module_;
  if (!(distance <= tolerance) && !scanned) {  // never trust the shortcut with a failure
    scan_all();
    foot(&s, &distance);
  }
  *distance_out = distance;
  *out = FlankPosition{tooth, flank, std::clamp(s, 0.0, arc_length_max())};
  return distance <= tolerance;
}

FlankPosition InfluenceTable::Locate(const Eigen::Vector2d& point, int tooth, int flank) const {
  FlankIndex(flank, "Locate");
  FlankPosition at;
  double distance = 0;
  if (!TryLocate(point, tooth, flank, &at, &distance)) {
    std::ostringstream msg;
    msg.precision(9);
    msg << "InfluenceTable::Locate: the point (" << point.x() * 1e3 << ", " << point.y() * 1e3
        << ") mm is " << distance * 1e3 << " mm from flank " << (flank > 0 ? "+" : "-")
        << " of tooth " << tooth << " of '" << gear_->name()
        << "' (form point to tip-round end); the rule is at most 1e-3 m = " << 1e-3 * module_ * 1e3
        << " mm";
    throw std::invalid_argument(msg.str());
  }
  return at;
}

double InfluenceTable::Compliance(const Eigen::Vector2d& load_point,
                                  const Eigen::Vector2d& load_normal, int load_tooth,
                                  int load_flank, const Eigen::Vector2d& response_point,
                                  const Eigen::Vector2d& response_normal, int response_tooth,
                                  int response_flank) const {
  const FlankPosition a = Locate(load_point, load_tooth, load_flank);
  const FlankPosition b = Locate(response_point, response_tooth, response_flank);
  return response_normal.dot(Influence(a, b) * load_normal);
}

Eigen::Matrix2d InfluenceTable::GridValue(int fl, int i, int k, int f, int j) const {
  if (raw_.empty()) {
    throw std::invalid_argument(
        "InfluenceTable::GridValue: the raw table is kept only by a table built in this process "
        "(a table loaded from the cache holds the symmetrised, joined values)");
  }
  Eigen::Matrix2d m;
  for (int c = 0; c < 2; ++c) {
    const std::size_t at = Index(fl, i, c, k, f, j);
    m(0, c) = raw_[at];
    m(1, c) = raw_[at + 1];
  }
  return m;
}

Eigen::Matrix2d InfluenceTable::SelfBlock(int fl, int i) const {
  return self_[static_cast<std::size_t>(fl) * n_ + i];
}

double InfluenceTable::LayerCompliance(int fl, int i) const {
  return layer_[static_cast<std::size_t>(fl) * n_ + i];
}

}  // namespace epicycle::compliance

namespace epicycle::compliance {
namespace {

using internal::Put;

template <typename T>
T Get(std::istream& in) {
  return internal::Get<T>(in, "influence table");
}

void PutVector(std::ostream& out, const std::vector<double>& v) {
  Put<std::uint64_t>(out, v.size());
  out.write(reinterpret_cast<const char*>(v.data()),
            static_cast<std::streamsize>(v.size() * sizeof(double)));
}

std::vector<double> GetVector(std::istream& in, std::size_t expected) {
  const auto size = Get<std::uint64_t>(in);
  if (size != expected) {
    throw std::runtime_error("influence table payload: array of " + std::to_string(size) +
                             " values where " + std::to_string(expected) + " were expected");
  }
  std::vector<double> v(expected);
  in.read(reinterpret_cast<char*>(v.data()),
          static_cast<std::streamsize>(expected * sizeof(double)));
  if (!in) throw std::runtime_error("influence table payload truncated");
  return v;
}

}  // namespace

void InfluenceTable::WritePayload(std::ostream& out) const {
  Put<std::int32_t>(out, teeth_);
  Put<std::int32_t>(out, n_);
  Put<std::int32_t>(out, num_dofs_);
  Put<std::int32_t>(out, num_elements_);
  for (double v : {depth_, max_depth_, module_, raw_asymmetry_, raw_self_asymmetry_, seconds_[0],
                   seconds_[1], seconds_[2], grid_.form_arc}) {
    Put(out, v);
  }
  std::vector<double> g;
  for (int i = 0; i < n_; ++i) {
    g.insert(g.end(), {grid_.arc_length[i], grid_.position[i].x(), grid_.position[i].y(),
                       grid_.normal[i].x(), grid_.normal[i].y()});
  }
  PutVector(out, g);
  PutVector(out, surface_);
  std::vector<double> s;
  for (const auto& m : self_) s.insert(s.end(), {m(0, 0), m(1, 0), m(0, 1), m(1, 1)});
  PutVector(out, s);
  PutVector(out, layer_);
  if (has_fillet_stress()) {
    Put<std::int32_t>(out, static_cast<std::int32_t>(fillet_.size()));
    std::vector<double> f;
    for (const FilletPoint& p : fillet_)
      f.insert(f.end(),
               {p.arc_length, p.position.x(), p.position.y(), p.tangent.x(), p.tangent.y()});
    PutVector(out, f);
    PutVector(out, fillet_stress_);
  }
}

InfluenceTable InfluenceTable::ReadPayload(std::istream& in, const geometry::Gear& gear,
                                           bool fillet_stress) {
  InfluenceTable t;
  t.teeth_ = Get<std::int32_t>(in);
  t.n_ = Get<std::int32_t>(in);
  t.num_dofs_ = Get<std::int32_t>(in);
  t.num_elements_ = Get<std::int32_t>(in);
  if (t.teeth_ != gear.teeth() || t.n_ < 4 || t.n_ > 100000) {
    throw std::runtime_error("influence table payload: " + std::to_string(t.teeth_) +
                             " teeth and " + std::to_string(t.n_) +
                             " grid points do not fit gear '" + gear.name() + "'");
  }
  t.depth_ = Get<double>(in);
  t.max_depth_ = Get<double>(in);
  t.module_ = Get<double>(in);
  t.raw_asymmetry_ = Get<double>(in);
  t.raw_self_asymmetry_ = Get<double>(in);
  for (auto& s : t.seconds_) s = Get<double>(in);
  t.grid_.form_arc = Get<double>(in);
  const int n = t.n_, z = t.teeth_;
  const std::vector<double> g = GetVector(in, static_cast<std::size_t>(5) * n);
  for (int i = 0; i < n; ++i) {
    t.grid_.arc_length.push_back(g[5 * i]);
    t.grid_.position.emplace_back(g[5 * i + 1], g[5 * i + 2]);
    t.grid_.normal.emplace_back(g[5 * i + 3], g[5 * i + 4]);
  }
  const std::size_t total = static_cast<std::size_t>(2) * n * 2 * z * 2 * n * 2;
  t.surface_ = GetVector(in, total);
  const std::vector<double> s = GetVector(in, static_cast<std::size_t>(8) * n);
  for (int k = 0; k < 2 * n; ++k) {
    Eigen::Matrix2d m;
    m << s[4 * k], s[4 * k + 2], s[4 * k + 1], s[4 * k + 3];
    t.self_.push_back(m);
  }
  t.layer_ = GetVector(in, static_cast<std::size_t>(2) * n);
  if (fillet_stress) {
    const int m = Get<std::int32_t>(in);
    if (m < 3 || m > 100000)
      throw std::runtime_error("influence table payload: " + std::to_string(m) +
                               " fillet points (3 to 100000 expected)");
    const std::vector<double> f = GetVector(in, static_cast<std::size_t>(5) * m);
    for (int j = 0; j < m; ++j)
      t.fillet_.push_back({f[5 * j], {f[5 * j + 1], f[5 * j + 2]}, {f[5 * j + 3], f[5 * j + 4]}});
    t.fillet_stress_ = GetVector(in, static_cast<std::size_t>(2) * n * 2 * z * 2 * m);
  }
  t.gear_ = std::make_shared<const geometry::Gear>(gear);
  t.path_ = std::make_shared<const ProfilePath>(*t.gear_);
  t.BuildDerived();
  return t;
}

void InfluenceTable::BuildDerived() {
  // The slope weights of the interpolant (Weights): the derivative at node m of the parabola
  // through grid points m0, m0 + 1, m0 + 2, m0 = clamp(m − 1, 0, n − 3), with spacings h0, h1.
  slope_.assign(static_cast<std::size_t>(n_), {});
  const std::vector<double>& g = grid_.arc_length;
  for (int m = 0; m < n_; ++m) {
    std::array<double, 3>& k = slope_[static_cast<std::size_t>(m)];
    if (m == 0) {
      const double h0 = g[1] - g[0], h1 = g[2] - g[1];
      k = {-(2 * h0 + h1) / (h0 * (h0 + h1)), (h0 + h1) / (h0 * h1), -h0 / (h1 * (h0 + h1))};
    } else if (m == n_ - 1) {
      const double h0 = g[m - 1] - g[m - 2], h1 = g[m] - g[m - 1];
      k = {h1 / (h0 * (h0 + h1)), -(h0 + h1) / (h0 * h1), (2 * h1 + h0) / (h1 * (h0 + h1))};
    } else {
      const double h0 = g[m] - g[m - 1], h1 = g[m + 1] - g[m];
      k = {-h1 / (h0 * (h0 + h1)), (h1 - h0) / (h0 * h1), h0 / (h1 * (h0 + h1))};
    }
  }
  // Weights' first guess of the interval of an arc length s: s (n − 1)/s_max.
  interval_scale_ = g.back() > 0.0 ? (n_ - 1) / g.back() : 0.0;
  // kDense points per grid interval, the grid nodes among them, taken from the exact profile.
  dense_.clear();
  dense_.reserve(static_cast<std::size_t>(n_ - 1) * kDense + 1);
  for (int i = 0; i + 1 < n_; ++i) {
    for (int m = 0; m < kDense; ++m) {
      const double s =
          grid_.arc_length[i] + (grid_.arc_length[i + 1] - grid_.arc_length[i]) * m / kDense;
      dense_.push_back({m == 0 ? grid_.position[i] : path_->Point(grid_.form_arc + s), s});
    }
  }
  dense_.push_back({grid_.position[n_ - 1], grid_.arc_length[n_ - 1]});
  // The bisection's keys (TryLocate): ±|x| along the profile, + if the radius rises from the form
  // point to the tip-round end (external teeth), − if it falls (internal), so that they rise.
  key_sign_ = dense_.back().point.norm() > dense_.front().point.norm() ? 1.0 : -1.0;
  dense_key_.clear();
  for (const DensePoint& d : dense_) dense_key_.push_back(key_sign_ * d.point.norm());
  // As many buckets as points, of equal width between the first and the last key; bucket b holds
  // the bisection's answers for keys between its edges e_b = origin + b / scale and e_b+1:
  // [first point ≥ e_b, first point ≥ e_b+1].
  bucket_.clear();
  const int buckets = static_cast<int>(dense_key_.size());
  bucket_origin_ = dense_key_.front();
  bucket_scale_ = buckets / (dense_key_.back() - dense_key_.front());
  if (std::is_sorted(dense_key_.begin(), dense_key_.end()) && std::isfinite(bucket_scale_) &&
      bucket_scale_ > 0.0) {
    for (int b = 0; b <= buckets; ++b) {
      const double edge = bucket_origin_ + b / bucket_scale_;
      bucket_.push_back(static_cast<int>(
          std::lower_bound(dense_key_.begin(), dense_key_.end(), edge) - dense_key_.begin()));
    }
  }
  tooth_rotation_.clear();
  for (int k = 0; k < teeth_; ++k) tooth_rotation_.push_back(Rot(k * gear_->pitch_angle()));
}

}  // namespace epicycle::compliance
