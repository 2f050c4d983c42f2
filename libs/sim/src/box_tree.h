// box_tree.h (internal) -- axis-aligned boxes, and a bounding-box hierarchy over a set of them
// (features' bounds or sweeps), built once from their centres (median
// splits along the widest axis, four boxes a leaf) and refitted bottom-up
// when the boxes move; and the traversal of two hierarchies (or one with
// itself) that reports every pair of boxes no farther apart than a reach
// along every axis. Used by the shared contact candidates
// (contact_candidates.h). The same boxes give the same pairs in the same
// order.
#pragma once

#include <vector>

#include "layers/sim/cloth.h"

namespace layers::sim::detail {

struct Box {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  bool overlaps(const Box& o) const { return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all(); }
};

// Boxes no farther apart than `reach` along every axis (false with NaN).
inline bool near(const Box& a, const Box& b, double reach) {
  return (a.lo.array() - reach <= b.hi.array()).all() && (b.lo.array() - reach <= a.hi.array()).all();
}

class BoxTree {
 public:
  // Builds over boxes[first, first + count) (all when count < 0; their
  // indices in `boxes` are reported); non-finite boxes are never reported.
  void build(const std::vector<Box>& boxes, int first = 0, int count = -1);
  // New boxes at the same indices.
  void refit(const std::vector<Box>& boxes);
  int size() const { return static_cast<int>(items_.size()); }

  // Calls f(i) for every box i within `reach` of `query`.
  template <class F>
  void query(const Box& query, double reach, F&& f) const;
  // Calls f(i, j) for every box i of `a` and j of `b` within `reach`.
  template <class F>
  static void pairs(const BoxTree& a, const BoxTree& b, double reach, F&& f);

 private:
  struct Node {
    Box box;
    int first = 0, count = 0;   // leaf: items_[first, first + count)
    int left = -1, right = -1;  // inner node: children (left = this + 1)
  };
  int make(int first, int count, std::vector<Vec3>& centres);

  std::vector<Node> nodes_;
  std::vector<int> items_;
  std::vector<Box> boxes_;  // per item, in items_ order
};

template <class F>
void BoxTree::pairs(const BoxTree& a, const BoxTree& b, double reach, F&& f) {
  if (a.nodes_.empty() || b.nodes_.empty()) return;
  std::vector<std::pair<int, int>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const Node& p = a.nodes_[i];
    const Node& q = b.nodes_[j];
    if (!near(p.box, q.box, reach)) continue;
    const bool pl = p.left < 0, ql = q.left < 0;
    if (pl && ql) {
      for (int s = p.first; s < p.first + p.count; ++s)
        for (int t = q.first; t < q.first + q.count; ++t)
          if (near(a.boxes_[s], b.boxes_[t], reach)) f(a.items_[s], b.items_[t]);
      continue;
    }
    // Descend the larger side (a leaf never).
    const bool split_p = !pl && (ql || p.count >= q.count);
    if (split_p) {
      stack.push_back({p.right, j});
      stack.push_back({p.left, j});
    } else {
      stack.push_back({i, q.right});
      stack.push_back({i, q.left});
    }
  }
}

template <class F>
void BoxTree::query(const Box& query, double reach, F&& f) const {
  if (nodes_.empty()) return;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!near(node.box, query, reach)) continue;
    if (node.left < 0) {
      for (int s = node.first; s < node.first + node.count; ++s)
        if (near(boxes_[s], query, reach)) f(items_[s]);
      continue;
    }
    stack[top++] = node.right;  // depth below 64: median splits halve the count
    stack[top++] = node.left;
  }
}

}  // namespace layers::sim::detail
