// The active-set Newton's face system (face_solver.hpp).
#include "face_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace epicycle::solvers::internal {

bool FaceSolver::Factor(const std::vector<int>& active, const Eigen::VectorXd& du) {
  if (have_ && du.size() == 0 && active == active_) return true;  // H_AA = C_AA: unchanged
  active_ = active;
  h_ = p_.C(active, active);
  if (du.size() > 0) h_.diagonal() += du;
  have_ = false;
  ++factorisations_;
  kron_ = FactorKronecker(du);
  if (kron_) {
    ++kronecker_factorisations_;
  } else if (!FactorH()) {
    return false;
  }
  if (m_ > 0) {
    ga_ = p_.G(Eigen::all, active_);
    if (kron_) {
      // G_A H_AA⁻¹ G_Aᵀ column by column through the Kronecker solve (m is small).
      y_.resize(static_cast<Eigen::Index>(active_.size()), m_);
      for (int k = 0; k < m_; ++k) y_.col(k) = HSolve(ga_.row(k).transpose());
      schur_ = ga_ * y_;
      schur_ = (0.5 * (schur_ + schur_.transpose())).eval();
    } else if (blocks_.empty()) {
      y_ = h_llt_.matrixL().solve(ga_.transpose());
      schur_ = y_.transpose() * y_;
    } else {
      schur_.setZero(m_, m_);
      for (std::size_t b = 0; b < blocks_.size(); ++b) {
        y_ = ga_(Eigen::all, blocks_[b]).transpose();
        block_llt_[b].matrixL().solveInPlace(y_);
        schur_.noalias() += y_.transpose() * y_;
      }
    }
    if (p_.has_support) schur_ += p_.S;
    s_llt_.compute(schur_);
    // A singular or nearly singular Schur complement would make the Cholesky factor garbage.
    // Then the eigen-decomposition (m is small) and, for each eigenvalue below 1e-13·max:
    //  - if its eigenvector v has Gᵀv ≈ 0 (redundant equalities: λ not unique) the component
    //    is dropped (minimum-norm step; it would change no gap anyway);
    //  - otherwise (G_A rank deficient because too few contacts of a member are active: the
    //    member is unsupported) the eigenvalue gets a ridge of 1e-12·max, a large rigid motion
    //    that closes the member's gaps, so that the next active set carries it.
    pinv_ = false;
    if (s_llt_.info() == Eigen::Success) {
      const auto d = s_llt_.matrixLLT().diagonal();
      const double ratio = d.minCoeff() / d.maxCoeff();
      pinv_ = !(ratio * ratio > 1e-14);
    } else {
      pinv_ = true;
    }
    if (pinv_) {
      s_eig_.compute(schur_);
      const Eigen::VectorXd& ev = s_eig_.eigenvalues();
      const double top = std::max(ev.cwiseAbs().maxCoeff(), 1e-300);
      const double g_norm = std::max(p_.G.cwiseAbs().maxCoeff(), 1e-300);
      inv_ev_.resize(m_);
      for (int k = 0; k < m_; ++k) {
        if (ev(k) > 1e-13 * top) {
          inv_ev_(k) = 1.0 / ev(k);
        } else {
          const double moves =
              (p_.G.transpose() * s_eig_.eigenvectors().col(k)).cwiseAbs().maxCoeff();
          inv_ev_(k) = moves <= 1e-10 * g_norm ? 0.0 : 1.0 / (std::max(ev(k), 0.0) + 1e-12 * top);
        }
      }
    }
  }
  have_ = true;
  return true;
}

void FaceSolver::Solve(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2,
                       Eigen::VectorXd* dxa, Eigen::VectorXd* dl) const {
  SolveOnce(r1, r2, dxa, dl);
  // One step of iterative refinement on the full face system (with equalities), and on H_AA
  // after a Kronecker solve (its factors match C to 1e-10·max|C| only).
  if (active_.empty() || (m_ == 0 && !kron_)) return;
  Eigen::VectorXd e1, e2, cx, cl;
  Residual(r1, r2, *dxa, *dl, &e1, &e2);
  SolveOnce(e1, e2, &cx, &cl);
  *dxa += cx;
  if (m_ > 0) *dl += cl;
}

// e = r − K d with the dense H_AA.
void FaceSolver::Residual(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2,
                          const Eigen::VectorXd& dxa, const Eigen::VectorXd& dl,
                          Eigen::VectorXd* e1, Eigen::VectorXd* e2) const {
  if (m_ == 0) {
    *e1 = r1 - h_ * dxa;
    e2->resize(0);
    return;
  }
  *e1 = r1 - (h_ * dxa - ga_.transpose() * dl);
  *e2 = r2 - ga_ * dxa;
  if (p_.has_support) *e2 -= p_.S * dl;
}

void FaceSolver::SolveOnce(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2,
                           Eigen::VectorXd* dxa, Eigen::VectorXd* dl) const {
  if (m_ == 0) {
    *dxa = HSolve(r1);
    dl->resize(0);
    return;
  }
  if (active_.empty()) {
    *dxa = Eigen::VectorXd();
    if (p_.has_support) {
      *dl = Eigen::LDLT<Eigen::MatrixXd>(p_.S).solve(r2);
      if (!dl->allFinite()) dl->setZero(m_);
    } else {
      dl->setZero(m_);
    }
    return;
  }
  const Eigen::VectorXd h_r1 = HSolve(r1);
  const Eigen::VectorXd rs = r2 - ga_ * h_r1;
  if (pinv_)
    *dl = s_eig_.eigenvectors() * inv_ev_.cwiseProduct(s_eig_.eigenvectors().transpose() * rs);
  else
    *dl = s_llt_.solve(rs);
  *dxa = HSolve(r1 + ga_.transpose() * *dl);
}

// Factorises h_: dense, or block by block over the slice groups of the active contacts.
bool FaceSolver::FactorH() {
  blocks_.clear();
  if (p_.slice_groups > 1) {
    const int na = static_cast<int>(active_.size());
    std::vector<std::vector<int>> by_group(static_cast<std::size_t>(p_.slice_groups));
    for (int a = 0; a < na; ++a)
      by_group[static_cast<std::size_t>(p_.slice_group[active_[a] % p_.slices])].push_back(a);
    for (auto& g : by_group)
      if (!g.empty()) blocks_.push_back(std::move(g));
  }
  if (blocks_.size() <= 1) {  // one group: the dense factorisation
    blocks_.clear();
    h_llt_.compute(h_);
    return h_llt_.info() == Eigen::Success;
  }
  block_llt_.resize(blocks_.size());
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    hb_ = h_(blocks_[b], blocks_[b]);
    block_llt_[b].compute(hb_);
    if (block_llt_[b].info() != Eigen::Success) return false;
  }
  return true;
}

// The Kronecker factorisation (face_solver.hpp) when the structure, the active set and the
// diagonal allow it; false leaves the dense (or block) path to factorise.
bool FaceSolver::FactorKronecker(const Eigen::VectorXd& du) {
  const Eigen::Index n_src = p_.kron_source.rows();
  if (n_src == 0 || du.size() == 0) return false;
  const int slices = p_.slices;
  const int na = static_cast<int>(active_.size());
  if (na == 0 || na % slices != 0) return false;
  const int nj = na / slices;
  std::vector<int> contacts(static_cast<std::size_t>(nj));
  Eigen::VectorXd d(nj);
  for (int k = 0; k < nj; ++k) {
    const int first = active_[static_cast<std::size_t>(k * slices)];
    if (first % slices != 0) return false;
    for (int s = 0; s < slices; ++s) {
      const int a = k * slices + s;
      if (active_[static_cast<std::size_t>(a)] != first + s || du(a) != du(k * slices))
        return false;
    }
    contacts[static_cast<std::size_t>(k)] = first / slices;
    d(k) = du(k * slices);
  }
  if (kq_.size() == 0) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(p_.kron_kernel);
    if (eig.info() != Eigen::Success) return false;
    kq_ = eig.eigenvectors();
    klambda_ = eig.eigenvalues();
  }
  // λ_s C_n,JJ + D_J is well conditioned when D_J > 0 (local terms) or the kernel is definite;
  // a near-singular block (λ_s ≈ 0 on a contact without a local term) is left to the dense path.
  if (!(d.minCoeff() > 0.0) && !(klambda_.minCoeff() > 1e-10 * klambda_.maxCoeff())) return false;
  const Eigen::MatrixXd cj = p_.kron_source(contacts, contacts);
  kron_llt_.resize(static_cast<std::size_t>(slices));
  Eigen::MatrixXd b;
  for (int s = 0; s < slices; ++s) {
    b = klambda_(s) * cj;
    b.diagonal() += d;
    kron_llt_[static_cast<std::size_t>(s)].compute(b);
    if (kron_llt_[static_cast<std::size_t>(s)].info() != Eigen::Success) return false;
  }
  blocks_.clear();
  return true;
}

// H_AA⁻¹ r.
Eigen::VectorXd FaceSolver::HSolve(const Eigen::VectorXd& r) const {
  if (kron_) {
    // r as an S×|J| matrix R (R(s, k) = r(k·S + s)); H = C ⊗ W + D ⊗ I acts on it as
    // W R C + R D, which Qᵀ(·) turns into Λ R̂ C + R̂ D: row s of R̂ solves (λ_s C + D).
    const int slices = p_.slices;
    const Eigen::Index nj = r.size() / slices;
    const Eigen::Map<const Eigen::MatrixXd> rm(r.data(), slices, nj);
    Eigen::MatrixXd hat = kq_.transpose() * rm;
    for (int s = 0; s < slices; ++s) {
      Eigen::VectorXd row = hat.row(s).transpose();
      kron_llt_[static_cast<std::size_t>(s)].solveInPlace(row);
      hat.row(s) = row.transpose();
    }
    Eigen::VectorXd out(r.size());
    Eigen::Map<Eigen::MatrixXd>(out.data(), slices, nj).noalias() = kq_ * hat;
    return out;
  }
  if (blocks_.empty()) return h_llt_.solve(r);
  Eigen::VectorXd out(r.size());
  Eigen::VectorXd rb;
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    rb = r(blocks_[b]);
    block_llt_[b].solveInPlace(rb);
    out(blocks_[b]) = rb;
  }
  return out;
}

}  // namespace epicycle::solvers::internal
