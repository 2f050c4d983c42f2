// ProjectiveSystem: assembly and factorisation of the global matrix, and the
// local/global iterations of one substep (see projective.h).
#include <algorithm>
#include <string>

#include "layers/core/error.h"
#include "projective.h"

namespace layers::sim::detail {

bool ProjectiveSystem::current(const Cloth& cloth, double h) const { return h_ == h && revision_ == cloth.revision(); }

void ProjectiveSystem::build(const Cloth& cloth, double h) {
  const int n = cloth.num_vertices();
  const Cloth::State& s = cloth.state();
  Triplets t;
  t.reserve(18 * cloth.membrane().size() + 16 * cloth.bending().size() + n);
  add_membrane_matrix(cloth, t);
  add_bending_matrix(cloth, t);
  // Inertia; fixed vertices (pinned or massless) get a weight that
  // dominates their row, and are then set exactly after each solve.
  double largest = 0;
  for (const auto& e : t) largest = std::max(largest, std::abs(e.value()));
  for (int i = 0; i < n; ++i) largest = std::max(largest, cloth.masses()[i] / (h * h));
  inertia_.resize(n);
  for (int i = 0; i < n; ++i) {
    inertia_[i] = s.inv_mass[i] == 0.0 ? 1e8 * largest : cloth.masses()[i] / (h * h);
    t.emplace_back(i, i, inertia_[i]);
  }
  base_.resize(n, n);
  base_.setFromTriplets(t.begin(), t.end());
  diagonal_ = base_.diagonal();
  ldlt_.analyzePattern(base_);
  permutation_.resize(n);
  const auto& p = ldlt_.permutationP().indices();
  for (int i = 0; i < n; ++i) permutation_[p[i]] = i;
  attachments_.assign(n, 0.0);
  factorise(base_, cloth.name());
  rhs_.resize(n);
  work_.resize(n);
  y_.resize(n);
  h_ = h;
  revision_ = cloth.revision();
}

void ProjectiveSystem::factorise(const Eigen::SparseMatrix<double>& matrix, const std::string& what) {
  ldlt_.factorize(matrix);
  if (ldlt_.info() != Eigen::Success) {
    throw Error("cloth '" + what + "': the projective dynamics matrix could not be factorised");
  }
}

void ProjectiveSystem::update_attachments(const std::vector<std::uint8_t>& wanted, double stiffness) {
  const int n = static_cast<int>(attachments_.size());
  int changed = 0, attached = 0;
  for (int i = 0; i < n; ++i) {
    const bool want = wanted[i] != 0 && stiffness > 0;
    changed += want != (attachments_[i] != 0.0);
    attached += want;
  }
  ++frames_since_factorisation_;
  if (changed == 0) return;
  if (frames_since_factorisation_ < 3 && changed * 4 <= attached) return;
  Eigen::SparseMatrix<double> a = base_;
  for (int i = 0; i < n; ++i) {
    attachments_[i] = wanted[i] != 0 && stiffness > 0 ? stiffness * diagonal_[i] : 0.0;
    if (attachments_[i] != 0.0) a.coeffRef(i, i) += attachments_[i];
  }
  factorise(a, "attachments");
  frames_since_factorisation_ = 0;
}

void ProjectiveSystem::solve_in_place(Vec3s& b) {
  const int n = static_cast<int>(b.size());
  const auto& l = ldlt_.matrixL().nestedExpression();
  const int* col = l.outerIndexPtr();
  const int* row = l.innerIndexPtr();
  const double* value = l.valuePtr();
  const auto& d = ldlt_.vectorD();
  for (int i = 0; i < n; ++i) work_[i] = b[permutation_[i]];
  for (int j = 0; j < n; ++j) {  // L y = P b
    const Vec3 yj = work_[j];
    for (int p = col[j]; p < col[j + 1]; ++p) work_[row[p]] -= value[p] * yj;
  }
  for (int j = 0; j < n; ++j) work_[j] /= d[j];
  for (int j = n - 1; j >= 0; --j) {  // L^T z = D^-1 y
    Vec3 zj = work_[j];
    for (int p = col[j]; p < col[j + 1]; ++p) zj -= value[p] * work_[row[p]];
    work_[j] = zj;
  }
  for (int i = 0; i < n; ++i) b[permutation_[i]] = work_[i];
}

void ProjectiveSystem::begin(const Cloth::State& s) { y_ = s.x; }

void ProjectiveSystem::iterate(const Cloth& cloth, Cloth::State& s, const Vec3s& extra) {
  const int n = cloth.num_vertices();
  for (int i = 0; i < n; ++i) rhs_[i] = inertia_[i] * (s.inv_mass[i] == 0.0 ? s.x_start[i] : y_[i]) + extra[i];
  add_membrane_projections(cloth, s.x, rhs_);
  solve_in_place(rhs_);
  for (int i = 0; i < n; ++i) s.x[i] = s.inv_mass[i] == 0.0 ? s.x_start[i] : rhs_[i];
}

}  // namespace layers::sim::detail
