// garment_slivers.cpp -- edge flips for faces flattened by the lift from
// UV to 3D (see flip_slivers in garment_pattern.h).
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "layers/garment/garment_pattern.h"
#include "layers/geometry/topology.h"

namespace layers::garment {
namespace {

// A tenth of the UV area: sewn panels are developed nearly isometrically,
// so a healthy face keeps about its UV area in 3D.
constexpr double kSliverRatio = 0.1;

double area3(const GarmentMesh& m, int a, int b, int c) {
  const body::Vec3 pa = m.vertices.row(a).cast<double>().transpose(), pb = m.vertices.row(b).cast<double>().transpose(),
                   pc = m.vertices.row(c).cast<double>().transpose();
  return 0.5 * (pb - pa).cross(pc - pa).norm();
}

// Signed UV area (positive: counter-clockwise).
double area2(const GarmentMesh& m, int a, int b, int c) {
  const double ux = m.uv(b, 0) - m.uv(a, 0), uy = m.uv(b, 1) - m.uv(a, 1);
  const double vx = m.uv(c, 0) - m.uv(a, 0), vy = m.uv(c, 1) - m.uv(a, 1);
  return 0.5 * (ux * vy - uy * vx);
}

bool is_sliver(const GarmentMesh& m, int f) {
  return area3(m, m.faces(f, 0), m.faces(f, 1), m.faces(f, 2)) <
         kSliverRatio * std::abs(area2(m, m.uv_faces(f, 0), m.uv_faces(f, 1), m.uv_faces(f, 2)));
}

// Flips the longest edge of one sliver; false when none can be flipped.
bool flip_one(GarmentMesh& m) {
  // Directed edge (a -> b) -> (face, corner of a).
  std::map<std::pair<int, int>, std::pair<int, int>> owner;
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) owner[{m.faces(f, k), m.faces(f, (k + 1) % 3)}] = {f, k};
  for (int f = 0; f < m.num_faces(); ++f) {
    if (!is_sliver(m, f)) continue;
    const double a3 = area3(m, m.faces(f, 0), m.faces(f, 1), m.faces(f, 2));
    // Corner k opposite the longest edge (k+1 -> k+2).
    int k = 0;
    double longest = -1;
    for (int j = 0; j < 3; ++j) {
      const double len = (m.vertices.row(m.faces(f, (j + 1) % 3)) - m.vertices.row(m.faces(f, (j + 2) % 3))).norm();
      if (len > longest) {
        longest = len;
        k = j;
      }
    }
    // This face: b (corner k), c, a; the edge c -> a is shared with the
    // neighbour a -> c -> d (consistent winding).
    const int b = k, c = (k + 1) % 3, a = (k + 2) % 3;
    const auto found = owner.find({m.faces(f, a), m.faces(f, c)});
    if (found == owner.end()) continue;  // an opening
    const int g = found->second.first, ga = found->second.second, gc = (ga + 1) % 3, gd = (ga + 2) % 3;
    if (m.panel[g] != m.panel[f] || m.uv_faces(g, ga) != m.uv_faces(f, a) || m.uv_faces(g, gc) != m.uv_faces(f, c))
      continue;  // across a seam: the two faces live in different UV charts
    const int va = m.faces(f, a), vb = m.faces(f, b), vc = m.faces(f, c), vd = m.faces(g, gd);
    const int ua = m.uv_faces(f, a), ub = m.uv_faces(f, b), uc = m.uv_faces(f, c), ud = m.uv_faces(g, gd);
    if (vb == vd) continue;
    // New faces (a, b, d) and (b, c, d): larger in 3D, same orientation in UV.
    const double before = std::min(a3, area3(m, va, vc, vd));
    const double after = std::min(area3(m, va, vb, vd), area3(m, vb, vc, vd));
    const double sign = area2(m, ua, ub, uc) >= 0 ? 1.0 : -1.0;
    if (!(after > before) || sign * area2(m, ua, ub, ud) <= 0 || sign * area2(m, ub, uc, ud) <= 0) continue;
    m.faces.row(f) << va, vb, vd;
    m.faces.row(g) << vb, vc, vd;
    m.uv_faces.row(f) << ua, ub, ud;
    m.uv_faces.row(g) << ub, uc, ud;
    return true;
  }
  return false;
}

}  // namespace

int repair_slivers(GarmentMesh& m) {
  // One flip per round (the edge table is rebuilt after it); each flip
  // makes the smaller face of its pair larger, so the rounds end.
  int repaired = 0;
  while (repaired < m.num_faces() && flip_one(m)) ++repaired;
  // What no flip fixes (two corners lifted onto the same 3D point, or the
  // longest edge on an opening): the corners that are not on an opening
  // move towards the mean of their neighbours, a few times.
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(m.vertices.rows()));
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) neighbours[m.faces(f, k)].push_back(m.faces(f, (k + 1) % 3));
  const std::vector<char> opening = geometry::boundary_vertices(m.faces, m.num_vertices());
  for (int round = 0; round < 10; ++round) {
    bool any = false;
    for (int f = 0; f < m.num_faces(); ++f) {
      if (!is_sliver(m, f)) continue;
      any = true;
      for (int k = 0; k < 3; ++k) {
        const int v = m.faces(f, k);
        if (opening[v]) continue;
        Eigen::RowVector3f mean = Eigen::RowVector3f::Zero();
        for (int n : neighbours[v]) mean += m.vertices.row(n);
        m.vertices.row(v) = 0.5f * m.vertices.row(v) + 0.5f * mean / static_cast<float>(neighbours[v].size());
      }
      ++repaired;
    }
    if (!any) break;
  }
  return repaired;
}

}  // namespace layers::garment
