// garment_develop.cpp -- flattening of a placed panel grid into its flat
// pattern piece (the UVs): arc-length coordinates as a start, then
// as-rigid-as-possible iterations on a coarsened grid, interpolated back.
#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/SVD>
#include <Eigen/Sparse>

#include "layers/garment/garment_pattern.h"
#include "layers/garment/garment_triangulate.h"

namespace layers::garment {
namespace {

// UVs by arc length: u along each row from the middle column, v along
// each column from the first row (the initial guess for develop()).
std::vector<Vec2> arc_length_net(const PanelGrid& g) {
  std::vector<Vec2> uv(g.points.size(), Vec2::Zero());
  const int mid = g.cols / 2;
  for (int i = 0; i < g.rows; ++i) {
    for (int j = mid + 1; j < g.cols; ++j)
      uv[i * g.cols + j].x() = uv[i * g.cols + j - 1].x() + (g.at(i, j) - g.at(i, j - 1)).norm();
    for (int j = mid - 1; j >= 0; --j)
      uv[i * g.cols + j].x() = uv[i * g.cols + j + 1].x() - (g.at(i, j) - g.at(i, j + 1)).norm();
  }
  for (int j = 0; j < g.cols; ++j)
    for (int i = 1; i < g.rows; ++i)
      uv[i * g.cols + j].y() = uv[(i - 1) * g.cols + j].y() + (g.at(i, j) - g.at(i - 1, j)).norm();
  return uv;
}

// Every `stride`-th index of 0..n-1, the last one always included.
std::vector<int> subsample(int n, int stride) {
  std::vector<int> out;
  for (int k = 0; k < n - 1; k += stride) out.push_back(k);
  out.push_back(n - 1);
  return out;
}

// As-rigid-as-possible flattening (local/global) of a triangulated grid,
// starting from `uv`.
void arap(const std::vector<body::Vec3>& points, const std::vector<std::array<int, 3>>& tris, std::vector<Vec2>& uv,
          int iterations) {
  const int n = static_cast<int>(points.size());
  struct Local {
    std::array<Vec2, 3> x;    // the 3D triangle laid flat
    std::array<double, 3> w;  // weight of the edge opposite corner k
  };
  std::vector<Local> local(tris.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const body::Vec3 &a = points[tris[t][0]], &b = points[tris[t][1]], &c = points[tris[t][2]];
    const body::Vec3 e1 = b - a, e2 = c - a;
    const double l1 = e1.norm();
    const body::Vec3 n3 = e1.cross(e2);
    Local& L = local[t];
    L.x = {Vec2::Zero(), Vec2(l1, 0.0), l1 > 0 ? Vec2(e1.dot(e2) / l1, n3.norm() / l1) : Vec2::Zero()};
    for (int k = 0; k < 3; ++k) {
      const Vec2 u = L.x[(k + 1) % 3] - L.x[k], v = L.x[(k + 2) % 3] - L.x[k];
      const double cross = std::abs(u.x() * v.y() - u.y() * v.x());
      const double cot = cross > 1e-14 ? u.dot(v) / cross : 0.0;
      L.w[k] = 0.5 * std::clamp(cot, 0.01, 10.0);
      const int i = tris[t][(k + 1) % 3], j = tris[t][(k + 2) % 3];
      entries.emplace_back(i, i, L.w[k]);
      entries.emplace_back(j, j, L.w[k]);
      entries.emplace_back(i, j, -L.w[k]);
      entries.emplace_back(j, i, -L.w[k]);
    }
  }
  const double pin = 1e6;
  entries.emplace_back(0, 0, pin);
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
  if (solver.info() != Eigen::Success) return;  // keep the initial guess
  Eigen::MatrixXd rhs(n, 2), sol(n, 2);
  for (int it = 0; it < iterations; ++it) {
    rhs.setZero();
    for (std::size_t t = 0; t < tris.size(); ++t) {
      const Local& L = local[t];
      Eigen::Matrix2d S = Eigen::Matrix2d::Zero();
      for (int k = 0; k < 3; ++k) {
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        S += L.w[k] * (uv[tris[t][a]] - uv[tris[t][b]]) * (L.x[a] - L.x[b]).transpose();
      }
      Eigen::JacobiSVD<Eigen::Matrix2d> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
      Eigen::Matrix2d U = svd.matrixU();
      if ((U * svd.matrixV().transpose()).determinant() < 0) U.col(1) *= -1;
      const Eigen::Matrix2d R = U * svd.matrixV().transpose();
      for (int k = 0; k < 3; ++k) {
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        const Vec2 d = L.w[k] * (R * (L.x[a] - L.x[b]));
        rhs.row(tris[t][a]) += d.transpose();
        rhs.row(tris[t][b]) -= d.transpose();
      }
    }
    rhs.row(0) += pin * uv[0].transpose();
    sol = solver.solve(rhs);
    for (int i = 0; i < n; ++i) uv[i] = sol.row(i).transpose();
  }
}

}  // namespace

std::vector<Vec2> develop(const PanelGrid& g) {
  // Flatten a grid of about 2 x the spacing, then interpolate.
  const std::vector<int> rows = subsample(g.rows, 2), cols = subsample(g.cols, 2);
  PanelGrid coarse(g.name, static_cast<int>(rows.size()), static_cast<int>(cols.size()));
  for (int i = 0; i < coarse.rows; ++i)
    for (int j = 0; j < coarse.cols; ++j) coarse.at(i, j) = g.at(rows[i], cols[j]);
  std::vector<Vec2> cuv = arc_length_net(coarse);
  std::vector<std::array<int, 3>> tris;
  for (int i = 0; i + 1 < coarse.rows; ++i)
    for (int j = 0; j + 1 < coarse.cols; ++j) {
      const int a = i * coarse.cols + j, b = a + 1, c = a + coarse.cols + 1, d = a + coarse.cols;
      tris.push_back({a, b, c});
      tris.push_back({a, c, d});
    }
  arap(coarse.points, tris, cuv, 12);
  // Hem (first row) along +u.
  const Vec2 dir = (cuv[coarse.cols - 1] - cuv[0]).normalized();
  const Eigen::Matrix2d rot = (Eigen::Matrix2d() << dir.x(), dir.y(), -dir.y(), dir.x()).finished();
  for (Vec2& q : cuv) q = rot * q;
  // Bilinear interpolation back onto every grid point.
  std::vector<Vec2> uv(g.points.size());
  auto locate = [](const std::vector<int>& ks, int k) {
    const int c = static_cast<int>(std::upper_bound(ks.begin(), ks.end(), k) - ks.begin()) - 1;
    const int c0 = std::min(c, static_cast<int>(ks.size()) - 2);
    return std::make_pair(c0, static_cast<double>(k - ks[c0]) / (ks[c0 + 1] - ks[c0]));
  };
  for (int i = 0; i < g.rows; ++i) {
    const auto [ci, fi] = locate(rows, i);
    for (int j = 0; j < g.cols; ++j) {
      const auto [cj, fj] = locate(cols, j);
      const int a = ci * coarse.cols + cj;
      uv[i * g.cols + j] = (1 - fi) * ((1 - fj) * cuv[a] + fj * cuv[a + 1]) +
                           fi * ((1 - fj) * cuv[a + coarse.cols] + fj * cuv[a + coarse.cols + 1]);
    }
  }
  return uv;
}

}  // namespace layers::garment
