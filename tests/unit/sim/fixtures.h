// fixtures.h -- small meshes for the solver tests, made here: rectangular
// cloth grids, an icosphere, a subdivided (optionally rounded) box, a
// capsule body and a bell-shaped garment (surfaces of revolution). Closed
// shapes are wound outwards.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "layers/geometry/mesh.h"

namespace layers::sim::test {

using geometry::Faces;
using geometry::Points;
using geometry::TriMesh;
using V3 = Eigen::Vector3d;

inline TriMesh make_mesh(const std::vector<V3>& v, const std::vector<std::array<int, 3>>& f) {
  TriMesh m;
  m.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i)
    m.vertices.row(static_cast<Eigen::Index>(i)) = v[i].cast<float>().transpose();
  m.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.faces.row(static_cast<Eigen::Index>(i)) << f[i][0], f[i][1], f[i][2];
  return m;
}

// A grid of (nu+1) x (nv+1) vertices spanning origin + [0,1] u_axis x
// [0,1] v_axis; normals along u_axis x v_axis. Vertex (i, j) is j*(nu+1)+i.
inline TriMesh grid(const V3& origin, const V3& u_axis, const V3& v_axis, int nu, int nv) {
  std::vector<V3> v;
  std::vector<std::array<int, 3>> f;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) v.push_back(origin + u_axis * (double(i) / nu) + v_axis * (double(j) / nv));
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
      // Alternate the diagonal so the mesh has no preferred shear direction.
      if ((i + j) % 2 == 0) {
        f.push_back({a, b, d});
        f.push_back({a, d, c});
      } else {
        f.push_back({a, b, c});
        f.push_back({b, d, c});
      }
    }
  return make_mesh(v, f);
}

// Merges vertices closer than eps (re-indexing faces; drops nothing else).
inline TriMesh weld(const TriMesh& m, double eps = 1e-6) {
  std::map<std::tuple<long, long, long>, int> seen;
  std::vector<int> remap(m.num_vertices());
  std::vector<V3> v;
  for (int i = 0; i < m.num_vertices(); ++i) {
    const V3 p = m.vertices.row(i).cast<double>().transpose();
    const auto key = std::make_tuple(std::lround(p.x() / eps), std::lround(p.y() / eps), std::lround(p.z() / eps));
    auto it = seen.find(key);
    if (it == seen.end()) {
      it = seen.emplace(key, static_cast<int>(v.size())).first;
      v.push_back(p);
    }
    remap[i] = it->second;
  }
  std::vector<std::array<int, 3>> f;
  for (int i = 0; i < m.num_faces(); ++i)
    f.push_back({remap[m.faces(i, 0)], remap[m.faces(i, 1)], remap[m.faces(i, 2)]});
  return make_mesh(v, f);
}

// Flips faces of a shape that is star-shaped around `center` so that
// normals point away from it.
inline void orient_outwards(TriMesh& m, const V3& center) {
  for (int i = 0; i < m.num_faces(); ++i) {
    const V3 a = m.vertices.row(m.faces(i, 0)).cast<double>().transpose();
    const V3 b = m.vertices.row(m.faces(i, 1)).cast<double>().transpose();
    const V3 c = m.vertices.row(m.faces(i, 2)).cast<double>().transpose();
    if ((b - a).cross(c - a).dot((a + b + c) / 3 - center) < 0) std::swap(m.faces(i, 1), m.faces(i, 2));
  }
}

inline TriMesh icosphere(const V3& center, double radius, int subdivisions) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<V3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& tri : f) {
      const int ab = midpoint(tri[0], tri[1]), bc = midpoint(tri[1], tri[2]), ca = midpoint(tri[2], tri[0]);
      next.push_back({tri[0], ab, ca});
      next.push_back({tri[1], bc, ab});
      next.push_back({tri[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  for (auto& p : v) p = center + radius * p;
  TriMesh m = make_mesh(v, f);
  orient_outwards(m, center);
  return m;
}

// A closed box of the given half extents, each side a grid of about
// `cell`-sized squares.
inline TriMesh box(const V3& center, const V3& half, double cell) {
  std::vector<TriMesh> sides;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      V3 origin = center, u = V3::Zero(), w = V3::Zero();
      origin[axis] += sign * half[axis];
      origin[a] -= half[a];
      origin[b] -= half[b];
      u[a] = 2 * half[a];
      w[b] = 2 * half[b];
      const int nu = std::max(1, int(std::lround(u.norm() / cell))),
                nw = std::max(1, int(std::lround(w.norm() / cell)));
      sides.push_back(grid(origin, u, w, nu, nw));
    }
  TriMesh m = weld(geometry::concatenate(sides));
  orient_outwards(m, center);
  return m;
}

// A box with rounded edges and corners (radius r): the cube of `box` with
// each vertex pushed to distance r from the inner box of half extents
// half - r. Smooth, like a body, so the nearest-vertex penetration test is
// meaningful on it.
inline TriMesh rounded_box(const V3& center, const V3& half, double r, double cell) {
  TriMesh m = box(center, half, cell);
  const V3 inner = half - V3::Constant(r);
  for (int i = 0; i < m.num_vertices(); ++i) {
    const V3 p = m.vertices.row(i).cast<double>().transpose() - center;
    const V3 q = p.cwiseMax(-inner).cwiseMin(inner);
    const V3 d = p - q;
    const V3 out = q + (d.norm() > 0 ? V3(r * d.normalized()) : V3::Zero());
    m.vertices.row(i) = (center + out).cast<float>().transpose();
  }
  return m;
}

// A surface of revolution about the vertical axis through `base`: the
// profile lists (radius, height) points from bottom to top; each ring gets
// about one vertex per `edge` of its circumference (at least 6), so there
// are no slivers near the axis, and a point with radius 0 becomes a pole.
// Faces are wound away from `inside` (a point the surface is star-shaped
// around).
inline TriMesh revolve(const V3& base, const std::vector<std::pair<double, double>>& profile, double edge,
                       const V3& inside) {
  const double pi = 3.14159265358979323846;
  std::vector<V3> v;
  std::vector<std::array<int, 3>> f;
  std::vector<int> first, count;
  std::vector<double> phase;
  for (std::size_t j = 0; j < profile.size(); ++j) {
    const auto [r, y] = profile[j];
    first.push_back(static_cast<int>(v.size()));
    const int n = r < 1e-12 ? 1 : std::max(6, int(std::lround(2 * pi * r / edge)));
    count.push_back(n);
    phase.push_back(0.5 * (j % 2));
    if (n == 1) {
      v.push_back(base + V3(0, y, 0));
      continue;
    }
    for (int i = 0; i < n; ++i) {
      const double a = 2 * pi * (i + phase.back()) / n;
      v.push_back(base + V3(r * std::cos(a), y, r * std::sin(a)));
    }
  }
  for (std::size_t j = 0; j + 1 < profile.size(); ++j) {
    const int la = first[j], na = count[j], lb = first[j + 1], nb = count[j + 1];
    if (na == 1 || nb == 1) {
      const int pole = na == 1 ? la : lb, ring = na == 1 ? lb : la, n = na == 1 ? nb : na;
      for (int i = 0; i < n; ++i) f.push_back({ring + i, ring + (i + 1) % n, pole});
      continue;
    }
    // Zip two rings together, always advancing the one whose next vertex
    // comes first in angle.
    auto angle = [&](int i, int n, double ph) { return (i + ph) / n; };
    int i = 0, k = 0;
    while (i < na || k < nb) {
      const bool advance_a = k >= nb || (i < na && angle(i + 1, na, phase[j]) <= angle(k + 1, nb, phase[j + 1]));
      if (advance_a) {
        f.push_back({la + i % na, la + (i + 1) % na, lb + k % nb});
        ++i;
      } else {
        f.push_back({la + i % na, lb + (k + 1) % nb, lb + k % nb});
        ++k;
      }
    }
  }
  TriMesh m = make_mesh(v, f);
  orient_outwards(m, inside);
  return m;
}

// Profile points from (r0, y0) to (r1, y1) in about `edge` steps, without
// the first point.
inline void line_to(std::vector<std::pair<double, double>>& p, double r1, double y1, double edge) {
  const auto [r0, y0] = p.back();
  const int n = std::max(1, int(std::lround(std::hypot(r1 - r0, y1 - y0) / edge)));
  for (int k = 1; k < n; ++k) p.push_back({r0 + (r1 - r0) * k / n, y0 + (y1 - y0) * k / n});
  p.push_back({r1, y1});
}

// A quarter circle of radius r about (0, yc) from the side (r, yc) to the
// pole (0, yc + sign r), sign = +1 up, -1 down, without the first point.
inline void dome_to_pole(std::vector<std::pair<double, double>>& p, double r, double yc, int sign, double edge) {
  const double pi = 3.14159265358979323846;
  const int n = std::max(2, int(std::lround(0.5 * pi * r / edge)));
  for (int k = 1; k <= n; ++k) {
    const double a = 0.5 * pi * k / n;
    p.push_back({k == n ? 0.0 : r * std::cos(a), yc + sign * r * std::sin(a)});
  }
}

// A capsule: a vertical cylinder of radius r from y = base.y to base.y +
// height (the cylindrical part) with hemispherical ends.
inline TriMesh capsule(const V3& base, double r, double height, double edge) {
  std::vector<std::pair<double, double>> p = {{0.0, -r}};
  {
    std::vector<std::pair<double, double>> down = {{r, 0.0}};
    dome_to_pole(down, r, 0.0, -1, edge);
    for (auto it = down.rbegin() + 1; it != down.rend(); ++it) p.push_back(*it);
  }
  line_to(p, r, height, edge);
  dome_to_pole(p, r, height, +1, edge);
  return revolve(base, p, edge, base + V3(0, height / 2, 0));
}

// A garment: an open hem at y = base.y, straight up for `length`, closed
// by a hemispherical top -- a bell hanging on the body's head.
inline TriMesh bell(const V3& base, double r, double length, double edge) {
  std::vector<std::pair<double, double>> p = {{r, 0.0}};
  line_to(p, r, length, edge);
  dome_to_pole(p, r, length, +1, edge);
  return revolve(base, p, edge, base + V3(0, length / 2, 0));
}

inline V3 centroid(const Points& p) { return p.cast<double>().colwise().mean().transpose(); }

inline double mean_distance(const Points& a, const Points& b) {
  return (a.cast<double>() - b.cast<double>()).rowwise().norm().mean();
}

}  // namespace layers::sim::test
