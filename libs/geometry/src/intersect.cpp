// Exact triangle crossings and the face hierarchy that finds them (see
// intersect.h).
#include "layers/geometry/intersect.h"

#include <algorithm>

namespace layers::geometry {

namespace {

// Six times the signed volume of tetrahedron (a, b, c, d): positive when d
// lies on the side of plane (a, b, c) that its normal (b - a) x (c - a)
// points to.
double orient(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return (b - a).cross(c - a).dot(d - a);
}

bool opposite(double s, double t) { return (s > 0 && t < 0) || (s < 0 && t > 0); }
bool same_strict(double s, double t, double u) { return (s > 0 && t > 0 && u > 0) || (s < 0 && t < 0 && u < 0); }

Vec3d corner(const TriMesh& mesh, int face, int k) {
  return mesh.vertices.row(mesh.faces(face, k)).cast<double>().transpose();
}

constexpr int kLeafSize = 4;

}  // namespace

bool segment_crosses_triangle(const Vec3d& p, const Vec3d& q, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  if (!opposite(orient(a, b, c, p), orient(a, b, c, q))) return false;
  // p and q straddle the plane: the segment meets the plane where the line
  // does, inside the triangle when the line passes inside all three sides.
  return same_strict(orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a));
}

bool triangles_cross(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0, const Vec3d& b1,
                     const Vec3d& b2) {
  // Quick rejection: one triangle wholly (or touching) on one side of the
  // other's plane cannot be crossed.
  const double s0 = orient(b0, b1, b2, a0), s1 = orient(b0, b1, b2, a1), s2 = orient(b0, b1, b2, a2);
  if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) return false;
  const double t0 = orient(a0, a1, a2, b0), t1 = orient(a0, a1, a2, b1), t2 = orient(a0, a1, a2, b2);
  if ((t0 >= 0 && t1 >= 0 && t2 >= 0) || (t0 <= 0 && t1 <= 0 && t2 <= 0)) return false;
  return segment_crosses_triangle(a0, a1, b0, b1, b2) || segment_crosses_triangle(a1, a2, b0, b1, b2) ||
         segment_crosses_triangle(a2, a0, b0, b1, b2) || segment_crosses_triangle(b0, b1, a0, a1, a2) ||
         segment_crosses_triangle(b1, b2, a0, a1, a2) || segment_crosses_triangle(b2, b0, a0, a1, a2);
}

FaceTree::FaceTree(const TriMesh& mesh) : mesh_(mesh) {
  const int n = mesh_.num_faces();
  boxes_.resize(static_cast<std::size_t>(n));
  std::vector<Eigen::Vector3f> centres(static_cast<std::size_t>(n));
  order_.reserve(static_cast<std::size_t>(n));
  for (int f = 0; f < n; ++f) {
    Eigen::AlignedBox3f box;
    bool finite = true;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3f x = mesh_.vertices.row(mesh_.faces(f, k)).transpose();
      finite = finite && x.allFinite();
      box.extend(x);
    }
    if (!finite) continue;  // crosses nothing; stays an empty box
    boxes_[f] = box;
    centres[f] = box.center();
    order_.push_back(f);
  }
  nodes_.reserve(2 * order_.size() / kLeafSize + 1);
  if (!order_.empty()) build(0, static_cast<int>(order_.size()), centres);
}

int FaceTree::build(int first, int count, std::vector<Eigen::Vector3f>& centres) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  if (count <= kLeafSize) {
    Eigen::AlignedBox3f box;
    for (int i = first; i < first + count; ++i) box.extend(boxes_[order_[i]]);
    nodes_[index].box = box;
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  // Split at the median centre along the widest axis of the centres (one
  // pass over them); the node's box is its children's, built bottom-up.
  Eigen::AlignedBox3f spread;
  for (int i = first; i < first + count; ++i) spread.extend(centres[order_[i]]);
  int axis = 0;
  spread.sizes().maxCoeff(&axis);
  const auto begin = order_.begin() + first, middle = begin + count / 2, end = begin + count;
  std::nth_element(begin, middle, end, [&](int a, int b) { return centres[a][axis] < centres[b][axis]; });
  const int left = build(first, count / 2, centres);
  const int right = build(first + count / 2, count - count / 2, centres);
  nodes_[index].left = left;
  nodes_[index].right = right;
  nodes_[index].box = nodes_[left].box.merged(nodes_[right].box);
  return index;
}

std::int64_t MeshCrossings::a_faces_crossing() const { return std::count(a_faces.begin(), a_faces.end(), 1); }

std::int64_t MeshCrossings::a_vertices_on_crossings() const {
  return std::count(a_vertices.begin(), a_vertices.end(), 1);
}

double MeshCrossings::a_vertex_share() const {
  if (a_vertices.empty()) return 0.0;
  return static_cast<double>(a_vertices_on_crossings()) / static_cast<double>(a_vertices.size());
}

namespace {

// Calls visit(f, g) for every face f of `a` and face g of the tree's mesh
// that cross, testing only the pairs that pass(f, g) lets through (a
// cheap filter before the exact test).
template <class Pass, class Visit>
void cross_pairs(const TriMesh& a, const FaceTree& tree, Pass&& pass, Visit&& visit) {
  const TriMesh& b = tree.mesh();
  for (int f = 0; f < a.num_faces(); ++f) {
    const Vec3d a0 = corner(a, f, 0), a1 = corner(a, f, 1), a2 = corner(a, f, 2);
    if (!a0.allFinite() || !a1.allFinite() || !a2.allFinite()) continue;
    Eigen::AlignedBox3f box(a0.cast<float>());
    box.extend(a1.cast<float>());
    box.extend(a2.cast<float>());
    tree.visit(box, [&](int g) {
      if (pass(f, g) && triangles_cross(a0, a1, a2, corner(b, g, 0), corner(b, g, 1), corner(b, g, 2))) visit(f, g);
    });
  }
}

}  // namespace

void visit_crossings(const TriMesh& a, const FaceTree& tree, const std::function<void(int, int)>& visit) {
  cross_pairs(
      a, tree, [](int, int) { return true; }, visit);
}

namespace {

// The crossings of `a` with the tree's mesh, counting the pairs (f, g)
// for which keep(f, g) holds.
template <class Keep>
MeshCrossings crossings_kept(const TriMesh& a, const FaceTree& tree, Keep&& keep) {
  MeshCrossings out;
  out.a_faces.assign(static_cast<std::size_t>(a.num_faces()), 0);
  out.a_vertices.assign(static_cast<std::size_t>(a.num_vertices()), 0);
  cross_pairs(a, tree, keep, [&](int f, int) {
    ++out.pairs;
    out.a_faces[f] = 1;
    for (int k = 0; k < 3; ++k) out.a_vertices[a.faces(f, k)] = 1;
  });
  return out;
}

}  // namespace

MeshCrossings crossings(const TriMesh& a, const FaceTree& tree) {
  return crossings_kept(a, tree, [](int, int) { return true; });
}

MeshCrossings body_crossings(const std::vector<TriMesh>& garments, const TriMesh& body) {
  return body_crossings(garments, FaceTree(body));
}

MeshCrossings body_crossings(const std::vector<TriMesh>& garments, const FaceTree& body) {
  return crossings(concatenate(garments), body);
}

MeshCrossings layer_crossings(const std::vector<TriMesh>& outer, const std::vector<TriMesh>& inner) {
  return crossings(concatenate(outer), concatenate(inner));
}

MeshCrossings self_crossings(const FaceTree& tree) {
  const TriMesh& mesh = tree.mesh();
  MeshCrossings out;
  out.a_faces.assign(static_cast<std::size_t>(mesh.num_faces()), 0);
  out.a_vertices.assign(static_cast<std::size_t>(mesh.num_vertices()), 0);
  const auto mark = [&](int f) {
    out.a_faces[f] = 1;
    for (int k = 0; k < 3; ++k) out.a_vertices[mesh.faces(f, k)] = 1;
  };
  // Each pair once (g > f), neighbours rejected before the exact test.
  const auto apart = [&](int f, int g) {
    if (g <= f) return false;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        if (mesh.faces(f, i) == mesh.faces(g, j)) return false;
      }
    }
    return true;
  };
  cross_pairs(mesh, tree, apart, [&](int f, int g) {
    ++out.pairs;
    mark(f);
    mark(g);
  });
  return out;
}

std::vector<char> grow_faces(const TriMesh& mesh, std::vector<char> faces, int rings) {
  for (int r = 0; r < rings; ++r) {
    std::vector<char> touched(static_cast<std::size_t>(mesh.num_vertices()), 0);
    for (int f = 0; f < mesh.num_faces(); ++f) {
      if (!faces[f]) continue;
      for (int k = 0; k < 3; ++k) touched[mesh.faces(f, k)] = 1;
    }
    for (int f = 0; f < mesh.num_faces(); ++f) {
      for (int k = 0; k < 3; ++k) faces[f] = faces[f] || touched[mesh.faces(f, k)];
    }
  }
  return faces;
}

MeshCrossings body_crossings(const std::vector<TriMesh>& garments, const FaceTree& body,
                             const std::vector<char>& skip) {
  return crossings_kept(concatenate(garments), body, [&](int, int g) { return !skip[g]; });
}

}  // namespace layers::geometry
