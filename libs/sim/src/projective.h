// projective.h (internal) -- the elastic part of a substep, by projective
// dynamics (local/global): implicit Euler over the substep h minimises
//   1/(2h^2) |x - y|_M^2 + sum_i w_i/2 |A_i x - p_i|^2
// where y is the predicted position and each energy term is the squared
// distance of a linear function of the positions (a deformed material axis,
// a hinge curvature vector) to a constraint set. The local step projects
// A_i x onto its set (p_i); the global step solves the constant, sparse,
// symmetric positive definite system
//   (M/h^2 + sum_i w_i A_i^T A_i) x = M/h^2 y + sum_i w_i A_i^T p_i
// for the three coordinates with one LDLT factorisation made when the cloth
// is first stepped (and again when h, the material or the pins change).
// The global solve spreads load across the whole garment at once, so the
// stretch under a load does not depend on the mesh resolution (plain
// Gauss-Seidel XPBD needs ~(vertices along the garment)^2 sweeps; see
// docs/sim.md).
//
// Contacts that support the garment enter the global solve as temporary
// attachments (as Bouaziz et al. 2014 suggest for collisions): a supported
// vertex gets an extra weight w_i on the diagonal and a target p_i in the
// right-hand side. The weights are chosen per frame; the matrix is
// refactorised (numerically: the sparsity pattern never changes) only when
// the set of attached vertices has changed by more than a quarter or three
// frames have passed, and in between the factorised weights are used: a
// vertex attached in the matrix but no longer supported follows its
// inertial prediction, a newly supported one waits for the next
// refactorisation (the contact projection holds it meanwhile). The targets
// move every iteration at no extra cost.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "layers/sim/cloth.h"

namespace layers::sim::detail {

using Triplets = std::vector<Eigen::Triplet<double>>;

// Energy terms of the membrane (membrane.cpp), per triangle:
//  - warp and weft stretch: 0.5 * Et * A * dist(f, {|f| <= 1})^2 and
//    0.5 * Ec * A * dist(f, {|f| >= 1})^2 (tension / compression moduli),
//  - shear: 0.5 * 2G * A * dist((fu, fv), {fu . fv = 0})^2, which is
//    0.5 * G * A * gamma^2 for a small shear angle gamma.
void add_membrane_matrix(const Cloth& cloth, Triplets& out);
void add_membrane_projections(const Cloth& cloth, const Vec3s& x, Vec3s& rhs);

// Isometric bending (bending.cpp): 0.5 * B * weight * |c|^2 with target 0
// (a flat rest state) -- purely quadratic, so it lives in the matrix only.
void add_bending_matrix(const Cloth& cloth, Triplets& out);

class ProjectiveSystem {
 public:
  // True when the factorisation matches this cloth, substep and revision.
  bool current(const Cloth& cloth, double h) const;
  // Assembles and factorises the matrix without attachments.
  void build(const Cloth& cloth, double h);
  // Diagonal of the matrix without attachments: the stiffness of each vertex
  // held by its neighbours and its inertia (N/m).
  const Eigen::VectorXd& diagonal() const { return diagonal_; }
  // Frame start: the vertices that want an attachment (weight `stiffness`
  // x diagonal); refactorises according to the policy above. `wanted` is
  // per vertex, non-zero for yes.
  void update_attachments(const std::vector<std::uint8_t>& wanted, double stiffness);
  // The weights in the factorised matrix (0: none).
  const std::vector<double>& attachment_weights() const { return attachments_; }

  // Starts a substep: state.x holds the predicted positions y.
  void begin(const Cloth::State& state);
  const Vec3s& predicted() const { return y_; }
  // One local/global iteration towards the substep's solution; `extra` is
  // added to the right-hand side: weight x target of the attachments plus
  // any external force (N). Pinned vertices stay at state.x_start.
  void iterate(const Cloth& cloth, Cloth::State& state, const Vec3s& extra);

 private:
  double h_ = 0;
  long revision_ = -1;
  int frames_since_factorisation_ = 0;
  void factorise(const Eigen::SparseMatrix<double>& matrix, const std::string& what);
  // x = A^-1 b for the three coordinates at once, through the LDLT factor
  // (P A P^T = L D L^T, L unit lower triangular, stored column-wise).
  void solve_in_place(Vec3s& b);

  Eigen::SparseMatrix<double> base_;  // without attachments
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  std::vector<int> permutation_;  // row i of P b is b[permutation_[i]]
  Eigen::VectorXd inertia_;       // m_i / h^2, or the pin weight for fixed vertices
  Eigen::VectorXd diagonal_;
  std::vector<double> attachments_;
  Vec3s y_, rhs_, work_;
};

}  // namespace layers::sim::detail
