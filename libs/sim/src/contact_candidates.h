// contact_candidates.h (internal) -- the one broad phase of the solver's
// feature contacts (docs/sim.md "Contact candidates"), kept across
// substeps: the collision pass, the layer edge-edge and the body edge-edge
// contacts all read their pairs from it.
//
// ContactLayout indexes every feature globally: cloth vertices first
// (cloth by cloth), then the body's; cloth edges and faces first, then the
// body's.
//
// ContactCandidates holds every pair of features that can come within the
// pair's reach while each cloth vertex v stays inside its bound, the box of
// half-side radius[v] around a reference position ref[v] set when the
// list was made, and the body moves along the sweep of the frame the list
// was made for:
//  - cloth vertex - cloth face and cloth edge - cloth edge of two cloths,
//    or of one cloth with self-contact (features sharing a vertex left
//    out), within the pass's gap; edges of cloths on different layers
//    within the layer edge reach;
//  - cloth vertex - body face and cloth face - body vertex within the gap,
//    cloth edge - body edge within the body edge reach.
// Proof of the rule: a feature's positions lie in the union of its
// vertices' bounds (a box), and the body's anywhere in the frame lie in
// its frame-swept box; two features whose boxes are farther apart than
// the reach along some axis cannot come within it. Bounds are grown by
// kSlack (far above the rounding of the comparisons).
//
// ensure() checks every cloth position a phase reads against its bound
// (O(vertices)); when some are outside, the pairs of their features are
// listed again with new bounds for them (a local refresh: a query of each
// feature in the hierarchies), and when many are (kLocalShare), the whole
// list is made again around the positions given (each vertex's reference:
// the later position moved
// kAhead times its motion between the two further along it; its radius:
// the margin plus that distance plus the motion, so that both positions
// given lie in the bound); when only the body's frame changed,
// only the body pairs are made again. Lists come from traversals of
// bounding-box hierarchies (box_tree.h: per cloth and kind of feature over
// the bounds, and over the body's frame-swept features), built once per
// layout and refitted after, so the same positions give the same pairs in
// the same order.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "box_tree.h"
#include "layers/geometry/mesh.h"
#include "layers/sim/cloth.h"

namespace layers::sim::detail {

struct ContactLayout {
  int cloth_vertices = 0, cloth_edges = 0, cloth_faces = 0;
  int body_vertices = 0;
  std::vector<int> offset, edge_offset,
      face_offset;                        // per cloth, its first global index (and one past the last cloth's)
  std::vector<int> owner;                 // per global vertex: its cloth, or -1 for the body
  std::vector<char> self;                 // per cloth: self-contact on
  std::vector<int> layer;                 // per cloth: its layer
  std::vector<std::array<int, 2>> edges;  // cloths' first, then the body's
  std::vector<std::array<int, 3>> faces;
  long revision = 0;  // counts the times it was laid out

  // Lays out the cloths and the body (faces, edges and a pose, for its
  // vertex count; null: no body) again when either changed; true if it did.
  bool update(const std::vector<Cloth>& cloths, const std::vector<std::array<int, 3>>* body_faces,
              const geometry::Edges* body_edges, const Vec3s* body_pose);

 private:
  std::vector<long> revisions_;
  const void* body_faces_ = nullptr;
  const void* body_edges_ = nullptr;
  int body_count_ = -1;
};

class ContactCandidates {
 public:
  static constexpr double kSlack = 1e-9;
  // How far ahead along its last motion a vertex's reference is put, in
  // multiples of that motion (0, 1, 2 and 4 within 5% of each other on
  // bench_sim's 1k and 4k walks with local refreshes).
  static constexpr double kAhead = 1;
  // While the vertices out of their bounds since the whole lists were made
  // are at most this share of the cloth vertices, only the pairs of their
  // features are listed again (a local refresh); beyond, the whole lists.
  static constexpr double kLocalShare = 0.1;

  // What the lists must hold: pairs within `gap` (every kind), edges of
  // two layers within `layer_edges`, cloth and body edges within
  // `body_edges` (a reach of 0 lists no pair of its kind); `margin` is the
  // room each cloth vertex gets around its reference. A change makes the
  // lists again at the next ensure().
  struct Reach {
    double gap = 0, layer_edges = 0, body_edges = 0, margin = 0;
    bool operator==(const Reach& o) const {
      return gap == o.gap && layer_edges == o.layer_edges && body_edges == o.body_edges && margin == o.margin;
    }
  };
  // The body over the frame: every body position a phase reads lies on
  // the straight line from `from` to `to`; `revision` names that sweep
  // (-1: unknown, made again at every ensure()). Null: no body.
  struct BodySweep {
    const Vec3s* from = nullptr;
    const Vec3s* to = nullptr;
    long revision = -1;
  };

  void set_reach(const Reach& reach);
  const Reach& reach() const { return reach_; }

  // Makes sure the lists hold every pair for cloth positions a(g) and b(g)
  // (g a global cloth vertex; two positions: a sweep's ends, or the same
  // twice). Returns true when the lists were made again.
  template <class A, class B>
  bool ensure(const ContactLayout& layout, A&& a, B&& b, const BodySweep& body) {
    const int n = layout.cloth_vertices;
    const bool laid = layout_stamp_ == &layout && revision_ == layout.revision && static_cast<int>(ref_.size()) == n;
    escaped_.clear();
    if (laid) {
      for (int g = 0; g < n; ++g)
        if (!within(g, a(g)) || !within(g, b(g))) escaped_.push_back(g);
    }
    const bool body_changed =
        body.from != body_.from || body.to != body_.to || body.revision != body_.revision || body.revision < 0;
    // Local refreshes leave the other bounds as they were: past a budget of
    // vertices refreshed since the whole lists were made, make them anew.
    if (!laid || static_cast<double>(refreshed_ + escaped_.size()) > kLocalShare * n) {
      refreshed_ = 0;
      from_.resize(static_cast<std::size_t>(n));
      to_.resize(from_.size());
      for (int g = 0; g < n; ++g) {
        from_[g] = a(g);
        to_[g] = b(g);
      }
      make(layout, body);
      return true;
    }
    if (!escaped_.empty()) {
      refreshed_ += static_cast<long>(escaped_.size());
      for (int g : escaped_) {
        from_[g] = a(g);
        to_[g] = b(g);
      }
      refresh(layout);
    }
    if (body_changed) make_body(layout, body);
    return !escaped_.empty() || body_changed;
  }

  // Pairs: (cloth vertex, cloth face) and (cloth edge, cloth edge, the
  // first the lower index), by global index; (cloth vertex, body face),
  // (cloth face, body vertex), (cloth edge, body edge), the body's features
  // counted from 0.
  const std::vector<std::array<int, 2>>& cloth_vertex_face() const { return vf_; }
  const std::vector<std::array<int, 2>>& cloth_edge_edge() const { return ee_; }
  // A body pair with the body feature's box over the frame (not grown),
  // kept beside it for the collision pass's box test.
  struct BodyPair {
    std::array<int, 2> ids;
    Box body;
  };
  const std::vector<BodyPair>& body_vertex_face() const { return body_vf_; }
  const std::vector<BodyPair>& body_face_vertex() const { return body_fv_; }
  const std::vector<std::array<int, 2>>& body_edge_edge() const { return body_ee_; }
  // The same edge pairs per contact, in the cloths' own edge indices:
  // (outer edge, inner edge) of cloths `inner` and `outer` on two layers
  // (inner below), and (cloth edge, body edge) of one cloth.
  const std::vector<std::array<int, 2>>& layer_edge_pairs(int inner, int outer) const {
    return layer_ee_[static_cast<std::size_t>(inner) * cloths_ + outer];
  }
  const std::vector<std::array<int, 2>>& body_edge_pairs(int cloth) const { return body_ee_by_cloth_[cloth]; }
  // The edge pairs above that are within the gap alone (what the
  // collision pass reads), in the same order.
  const std::vector<std::array<int, 2>>& cloth_edge_edge_gap() const { return ee_gap_; }
  const std::vector<BodyPair>& body_edge_edge_gap() const { return body_ee_gap_; }
  // The body's features' boxes over the frame's sweep (not grown).
  const std::vector<Box>& body_vertex_boxes() const { return body_vertex_boxes_; }
  const std::vector<Box>& body_edge_boxes() const { return body_edge_boxes_; }
  const std::vector<Box>& body_face_boxes() const { return body_face_boxes_; }

  long builds() const { return builds_; }            // times the whole lists were made
  long refreshes() const { return refreshes_; }      // times they were refreshed locally
  long body_builds() const { return body_builds_; }  // times the body pairs alone were made

 private:
  bool within(int g, const Vec3& p) const {
    const Vec3 d = (p - ref_[g]).cwiseAbs();
    const double r = radius_[g];
    return d.x() <= r && d.y() <= r && d.z() <= r;  // false for NaN
  }
  void make(const ContactLayout& layout, const BodySweep& body);
  // The local refresh: escaped_ (from_ and to_ set for them) get new
  // bounds, and the pairs of their features are listed again.
  void refresh(const ContactLayout& layout);
  void set_bound(int g);                         // ref_, radius_ and vertex box of vertex g from from_ and to_
  Box feature_bound(const int* v, int n) const;  // the union of its vertices' bounds
  double edge_reach(const ContactLayout& layout, int c, int d) const;  // edges of cloths c and d
  // Each adds a pair to every list it belongs to.
  void add_vertex_face(const ContactLayout& layout, int v, int f);
  void add_edge_edge(const ContactLayout& layout, int e, int o);
  void add_body_edge(const ContactLayout& layout, int e, int i);
  void make_body(const ContactLayout& layout, const BodySweep& body);
  // The body's boxes over the sweep and its hierarchies fitted to them.
  void fit_body(const ContactLayout& layout, const BodySweep& body, bool any);
  // The body pairs of the cloths' bounds.
  void traverse_body(const ContactLayout& layout);

  Reach reach_;
  const ContactLayout* layout_stamp_ = nullptr;
  long revision_ = -1;
  Vec3s from_, to_;                                                // scratch: the positions given to the last make()
  Vec3s ref_;                                                      // per cloth vertex: its reference
  std::vector<double> radius_;                                     // and the half-side of its bound
  std::vector<Box> vertex_boxes_, edge_boxes_, face_boxes_;        // bounds of the cloth features (not grown)
  std::vector<BoxTree> vertex_trees_, edge_trees_, face_trees_;    // per cloth, over the bounds
  long tree_revision_ = -1;                                        // the layout they were built for
  std::vector<int> vertex_edge_start_, vertex_edges_;              // per cloth vertex: its edges ...
  std::vector<int> vertex_face_start_, vertex_faces_;              // ... and faces
  std::vector<int> escaped_;                                       // scratch: vertices out of their bounds
  long refreshed_ = 0;                                             // vertices refreshed since the last make()
  std::vector<std::uint8_t> vertex_mark_, edge_mark_, face_mark_;  // scratch: features to list again
  std::vector<int> marked_edges_, marked_faces_;
  std::vector<std::array<int, 2>> vf_, ee_, body_ee_, ee_gap_;
  std::vector<BodyPair> body_vf_, body_fv_, body_ee_gap_;
  std::vector<std::vector<std::array<int, 2>>> layer_ee_;  // per inner x cloths_ + outer
  std::size_t cloths_ = 0;
  std::vector<std::vector<std::array<int, 2>>> body_ee_by_cloth_;  // per cloth
  BodySweep body_;
  std::vector<Box> body_vertex_boxes_, body_edge_boxes_, body_face_boxes_;
  BoxTree body_vertex_tree_, body_edge_tree_, body_face_tree_;  // over the frame-swept boxes
  bool body_trees_built_ = false;
  bool body_listed_ = false;  // the body pairs are listed (a body and its sweep were given)
  long body_layout_ = -1;     // the layout revision the body's boxes were fitted for
  long builds_ = 0, body_builds_ = 0, refreshes_ = 0;
};

}  // namespace layers::sim::detail
