#include "epicycle/compliance/damaged_influence.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <istream>
#include <ostream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "payload_io.hpp"

namespace epicycle::compliance {

DamagedInfluence DamagedInfluence::Build(const geometry::Gear& gear,
                                         const ElasticMaterial& material, const RootCrack& crack,
                                         const InfluenceTableOptions& options, int neighbours,
                                         const CrackMeshOptions& crack_options) {
  InfluenceTableOptions opts = options;
  opts.fillet_stress = false;
  opts.Validate();
  material.Validate();
  const int z = gear.teeth();
  if (neighbours < 0 || neighbours >= z)
    throw std::invalid_argument("DamagedInfluence: neighbours = " + std::to_string(neighbours) +
                                ": must be in [0, " + std::to_string(z) + ") (teeth of '" +
                                gear.name() + "')");
  const double t0 = static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
  CrackedBodyMesh cracked = BuildCrackedGearMesh(gear, crack, opts.mesh, crack_options);
  const double t_mesh = static_cast<double>(std::clock()) / CLOCKS_PER_SEC - t0;
  DamagedInfluence d;
  d.crack_ = crack;
  d.neighbours_ = neighbours;
  d.teeth_ = z;
  d.sector_elements_ = cracked.sector_elements;
  d.row_of_tooth_.assign(static_cast<std::size_t>(z), -1);
  std::vector<int> load_teeth;
  for (int k = -neighbours; k <= neighbours; ++k) {
    const int t = ((crack.tooth + k) % z + z) % z;
    if (d.row_of_tooth_[t] >= 0) continue;
    d.row_of_tooth_[t] = static_cast<int>(load_teeth.size());
    load_teeth.push_back(t);
  }
  d.rows_ = InfluenceTable::SolveLoads(gear, material, opts, std::move(cracked.body), t_mesh,
                                       load_teeth, false);
  d.num_dofs_ = d.rows_.front().num_dofs();
  d.seconds_ = d.rows_.front().build_seconds();
  for (std::size_t q = 1; q < d.rows_.size(); ++q) d.seconds_[2] += d.rows_[q].seconds_[2];

  // Maxwell–Betti over the pairs of D: a = (t_a, fl, i) → b = (t_b, fr, j) is held by table A (its
  // frame: R_a) and b → a by table B. M = ½ (R_a A R_aᵀ + (R_b B R_bᵀ)ᵀ) goes back to both.
  const int n = d.rows_.front().n_;
  const double pitch = gear.pitch_angle();
  auto rot = [&](int k) { return Eigen::Rotation2Dd(k * pitch).toRotationMatrix(); };
  auto norm = [](const Eigen::Matrix2d& m) { return m.cwiseAbs().maxCoeff(); };
  auto read = [&](const InfluenceTable& tab, int fl, int i, int dk, int fr, int j) {
    Eigen::Matrix2d m;
    for (int c = 0; c < 2; ++c) {
      const std::size_t at = tab.Index(fl, i, c, dk, fr, j);
      m(0, c) = tab.surface_[at];
      m(1, c) = tab.surface_[at + 1];
    }
    return m;
  };
  auto write = [&](InfluenceTable& tab, int fl, int i, int dk, int fr, int j,
                   const Eigen::Matrix2d& m) {
    for (int c = 0; c < 2; ++c) {
      const std::size_t at = tab.Index(fl, i, c, dk, fr, j);
      tab.surface_[at] = m(0, c);
      tab.surface_[at + 1] = m(1, c);
    }
  };
  double asym = 0.0;
  const int held = static_cast<int>(load_teeth.size());
  for (int qa = 0; qa < held; ++qa) {
    for (int qb = qa; qb < held; ++qb) {
      InfluenceTable& ta = d.rows_[qa];
      InfluenceTable& tb = d.rows_[qb];
      const int a = load_teeth[qa], b = load_teeth[qb];
      const int dab = ((b - a) % z + z) % z, dba = ((a - b) % z + z) % z;
      const Eigen::Matrix2d ra = rot(a), rb = rot(b);
      for (int fl = 0; fl < 2; ++fl) {
        for (int i = 0; i < n; ++i) {
          const double da = norm(ta.self_[static_cast<std::size_t>(fl) * n + i]);
          for (int fr = 0; fr < 2; ++fr) {
            for (int j = 0; j < n; ++j) {
              if (qa == qb && (fr < fl || (fr == fl && j <= i))) continue;  // each pair once
              const double db = norm(tb.self_[static_cast<std::size_t>(fr) * n + j]);
              const Eigen::Matrix2d ab = ra * read(ta, fl, i, dab, fr, j) * ra.transpose();
              const Eigen::Matrix2d ba = rb * read(tb, fr, j, dba, fl, i) * rb.transpose();
              asym = std::max(asym, norm(ab - ba.transpose()) / std::sqrt(da * db));
              const Eigen::Matrix2d m = 0.5 * (ab + ba.transpose());
              write(ta, fl, i, dab, fr, j, ra.transpose() * m * ra);
              write(tb, fr, j, dba, fl, i, rb.transpose() * m.transpose() * rb);
            }
          }
        }
      }
    }
  }
  d.raw_asymmetry_ = asym;
  return d;
}

bool DamagedInfluence::HoldsLoadsOn(int tooth) const {
  return row_of_tooth_[static_cast<std::size_t>(((tooth % teeth_) + teeth_) % teeth_)] >= 0;
}

const InfluenceTable& DamagedInfluence::Rows(int tooth) const {
  const int q = row_of_tooth_[static_cast<std::size_t>(((tooth % teeth_) + teeth_) % teeth_)];
  if (q < 0)
    throw std::invalid_argument("DamagedInfluence::Rows: tooth " + std::to_string(tooth) +
                                " is not within " + std::to_string(neighbours_) +
                                " teeth of the cracked tooth " + std::to_string(crack_.tooth));
  return rows_[static_cast<std::size_t>(q)];
}

double DamagedInfluence::DirectedCompliance(const InfluenceTable& healthy,
                                            const InfluenceTable::DirectedNode& load,
                                            const InfluenceTable::DirectedNode& response) const {
  // DirectedNode::tooth is already reduced to [0, z).
  const int ql = row_of_tooth_[static_cast<std::size_t>(load.tooth)];
  if (ql >= 0) return rows_[static_cast<std::size_t>(ql)].DirectedCompliance(load, response);
  const int qr = row_of_tooth_[static_cast<std::size_t>(response.tooth)];
  // d_rᵀ Λ(l → r) d_l = d_lᵀ Λ(r → l) d_r: the response's row, read with the roles swapped.
  if (qr >= 0) return rows_[static_cast<std::size_t>(qr)].DirectedCompliance(response, load);
  return healthy.DirectedCompliance(load, response);
}

Eigen::Matrix2d DamagedInfluence::Influence(const InfluenceTable& healthy,
                                            const FlankPosition& load,
                                            const FlankPosition& response) const {
  if (HoldsLoadsOn(load.tooth)) return Rows(load.tooth).Influence(load, response);
  if (HoldsLoadsOn(response.tooth))
    return Rows(response.tooth).Influence(response, load).transpose();
  return healthy.Influence(load, response);
}

namespace {

using internal::Put;

template <typename T>
T Get(std::istream& in) {
  return internal::Get<T>(in, "damaged influence");
}

}  // namespace

void DamagedInfluence::WritePayload(std::ostream& out) const {
  Put<std::int32_t>(out, neighbours_);
  Put<std::int32_t>(out, teeth_);
  Put<std::int32_t>(out, num_dofs_);
  Put<std::int32_t>(out, sector_elements_);
  Put(out, raw_asymmetry_);
  for (double v : seconds_) Put(out, v);
  Put<std::int32_t>(out, static_cast<std::int32_t>(rows_.size()));
  for (int t = 0; t < teeth_; ++t)
    if (row_of_tooth_[static_cast<std::size_t>(t)] >= 0) {
      Put<std::int32_t>(out, t);
      Put<std::int32_t>(out, row_of_tooth_[static_cast<std::size_t>(t)]);
    }
  for (const InfluenceTable& row : rows_) row.WritePayload(out);
}

DamagedInfluence DamagedInfluence::ReadPayload(std::istream& in, const geometry::Gear& gear,
                                               const RootCrack& crack) {
  DamagedInfluence d;
  d.crack_ = crack;
  d.neighbours_ = Get<std::int32_t>(in);
  d.teeth_ = Get<std::int32_t>(in);
  d.num_dofs_ = Get<std::int32_t>(in);
  d.sector_elements_ = Get<std::int32_t>(in);
  d.raw_asymmetry_ = Get<double>(in);
  for (double& v : d.seconds_) v = Get<double>(in);
  const int z = gear.teeth();
  const int held = Get<std::int32_t>(in);
  if (d.teeth_ != z || d.neighbours_ < 0 || d.neighbours_ >= z || held < 1 ||
      held > std::min(z, 2 * d.neighbours_ + 1))
    throw std::runtime_error("damaged influence payload: " + std::to_string(d.teeth_) + " teeth, " +
                             std::to_string(d.neighbours_) + " neighbours and " +
                             std::to_string(held) + " row tables do not fit gear '" + gear.name() +
                             "'");
  d.row_of_tooth_.assign(static_cast<std::size_t>(z), -1);
  std::vector<char> used(static_cast<std::size_t>(held), 0);
  for (int q = 0; q < held; ++q) {
    const int t = Get<std::int32_t>(in), row = Get<std::int32_t>(in);
    const int away = std::min(((t - crack.tooth) % z + z) % z, ((crack.tooth - t) % z + z) % z);
    if (t < 0 || t >= z || row < 0 || row >= held || away > d.neighbours_ ||
        d.row_of_tooth_[static_cast<std::size_t>(t)] >= 0 || used[static_cast<std::size_t>(row)])
      throw std::runtime_error("damaged influence payload: row table " + std::to_string(row) +
                               " of tooth " + std::to_string(t) +
                               " does not fit a crack in tooth " + std::to_string(crack.tooth) +
                               " with " + std::to_string(d.neighbours_) + " neighbours");
    d.row_of_tooth_[static_cast<std::size_t>(t)] = row;
    used[static_cast<std::size_t>(row)] = 1;
  }
  for (int q = 0; q < held; ++q) d.rows_.push_back(InfluenceTable::ReadPayload(in, gear, false));
  return d;
}

}  // namespace epicycle::compliance
