// layers/geometry/intersect.h -- exact crossings between triangle meshes.
//
// Two triangles cross when an edge of one passes through the inside of the
// other: the edge's end points lie strictly on opposite sides of the other
// triangle's plane, and the edge's line passes strictly inside all three of
// its sides (signs of 3x3 determinants in double precision). Two triangles
// that intersect transversally always have such an edge. Touching is not
// crossing: a vertex resting on a face, an edge lying along a face, or two
// coplanar triangles that overlap all give a zero sign somewhere and do not
// count. Unlike the nearest-vertex test of penetration.h this is no
// heuristic: a garment face either passes through a body face or it does
// not, however coarse either mesh is.
//
// FaceTree (a bounding-volume hierarchy over one mesh's faces) keeps
// crossings() near-linear in the face counts. Faces with a non-finite
// coordinate cross nothing.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "layers/geometry/mesh.h"

namespace layers::geometry {

using Vec3d = Eigen::Vector3d;

// The segment p-q passes through the inside of triangle (a, b, c).
bool segment_crosses_triangle(const Vec3d& p, const Vec3d& q, const Vec3d& a, const Vec3d& b, const Vec3d& c);
// Triangle (a0, a1, a2) and triangle (b0, b1, b2) cross (an edge of either
// passes through the inside of the other).
bool triangles_cross(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0, const Vec3d& b1,
                     const Vec3d& b2);

// A bounding-volume hierarchy over the faces of a mesh (the mesh is
// copied; boxes are built once).
class FaceTree {
 public:
  explicit FaceTree(const TriMesh& mesh);

  const TriMesh& mesh() const { return mesh_; }
  // Calls visit(face) for every face whose box overlaps `box` (a template:
  // it runs for every candidate of every query, the measures' hot path).
  template <class F>
  void visit(const Eigen::AlignedBox3f& box, F&& visit) const {
    if (nodes_.empty() || box.isEmpty()) return;
    int stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!node.box.intersects(box)) continue;
      if (node.left < 0) {
        for (int i = node.first; i < node.first + node.count; ++i) {
          if (boxes_[order_[i]].intersects(box)) visit(order_[i]);
        }
        continue;
      }
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }

 private:
  struct Node {
    Eigen::AlignedBox3f box;
    int first = 0, count = 0;  // leaf: faces order_[first, first + count)
    int left = -1, right = -1;
  };
  int build(int first, int count, std::vector<Eigen::Vector3f>& centres);

  TriMesh mesh_;
  std::vector<Eigen::AlignedBox3f> boxes_;  // per face; empty box when non-finite
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

// The crossings of mesh `a` with mesh `b`.
struct MeshCrossings {
  std::int64_t pairs = 0;        // crossing (face of a, face of b) pairs
  std::vector<char> a_faces;     // per face of a: crosses a face of b
  std::vector<char> a_vertices;  // per vertex of a: on a face that crosses b
  std::int64_t a_faces_crossing() const;
  std::int64_t a_vertices_on_crossings() const;
  // a_vertices_on_crossings() / a's vertex count (0 for an empty mesh).
  double a_vertex_share() const;
};

MeshCrossings crossings(const TriMesh& a, const FaceTree& b);
// Calls visit(face of a, face of b) for every crossing pair, faces of a in
// order (what crossings() counts).
void visit_crossings(const TriMesh& a, const FaceTree& b, const std::function<void(int, int)>& visit);
inline MeshCrossings crossings(const TriMesh& a, const TriMesh& b) { return crossings(a, FaceTree(b)); }

// The two crossing measures of docs/metrics.md, shared by the generator's
// validation, `layers validate --physics` and every evaluation:
//  - body crossings: every garment (as one mesh, vertices in order) against
//    the body; a_vertex_share() is the share of garment vertices on a
//    garment face that passes through the body surface.
//  - layer crossings: the outer garments against the inner ones; the share
//    of outer vertices on an outer face that passes through an inner face.
//    Garments of one layer are not tested against each other.
MeshCrossings body_crossings(const std::vector<TriMesh>& garments, const TriMesh& body);
// The same against a body tree built once (e.g. for the predicted and the
// true garments of one frame).
MeshCrossings body_crossings(const std::vector<TriMesh>& garments, const FaceTree& body);
MeshCrossings layer_crossings(const std::vector<TriMesh>& outer, const std::vector<TriMesh>& inner);

// Self-crossings of one mesh (`tree` is built over it): a_faces marks the
// faces that pass through another face of the same mesh, pairs that share
// a vertex skipped (neighbours meet along their shared edge or corner by
// construction); pairs counts each crossing pair once. A posed body whose
// arm sinks into its torso has self-crossings along the seam; a garment
// laid over both must cross one of them there.
MeshCrossings self_crossings(const FaceTree& tree);
// `faces` grown by `rings` rings of neighbours (faces sharing a vertex).
std::vector<char> grow_faces(const TriMesh& mesh, std::vector<char> faces, int rings);
// Body crossings that leave out the body faces marked in `skip` (one flag
// per body face): the garment crossings that a body free of its own
// crossings could avoid.
MeshCrossings body_crossings(const std::vector<TriMesh>& garments, const FaceTree& body, const std::vector<char>& skip);

}  // namespace layers::geometry
