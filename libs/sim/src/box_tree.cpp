// BoxTree (see box_tree.h): median-split build over box centres, bottom-up
// refit.
#include "box_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace layers::sim::detail {

namespace {

constexpr int kLeaf = 4;

Box merge(const Box& a, const Box& b) { return Box{a.lo.cwiseMin(b.lo), a.hi.cwiseMax(b.hi)}; }

}  // namespace

void BoxTree::build(const std::vector<Box>& boxes, int first, int count) {
  const int n = count < 0 ? static_cast<int>(boxes.size()) - first : count;
  items_.resize(static_cast<std::size_t>(n));
  std::iota(items_.begin(), items_.end(), first);
  // Centres by global index (a vector as long as `boxes`).
  std::vector<Vec3> centres(boxes.size(), Vec3::Zero());
  for (int i = first; i < first + n; ++i) {
    const Vec3 c = 0.5 * (boxes[i].lo + boxes[i].hi);
    centres[i] = c.allFinite() ? c : Vec3::Zero();
  }
  nodes_.clear();
  nodes_.reserve(static_cast<std::size_t>(2 * (n / kLeaf + 1)));
  if (n > 0) make(0, n, centres);
  refit(boxes);
}

int BoxTree::make(int first, int count, std::vector<Vec3>& centres) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back(Node{});
  nodes_[index].first = first;
  nodes_[index].count = count;
  if (count <= kLeaf) return index;
  Vec3 lo = centres[items_[first]], hi = lo;
  for (int k = first; k < first + count; ++k) {
    lo = lo.cwiseMin(centres[items_[k]]);
    hi = hi.cwiseMax(centres[items_[k]]);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(items_.begin() + first, items_.begin() + first + half, items_.begin() + first + count,
                   [&](int a, int b) {
                     const double u = centres[a][axis], v = centres[b][axis];
                     return u < v || (u == v && a < b);
                   });
  const int left = make(first, half, centres);
  const int right = make(first + half, count - half, centres);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

void BoxTree::refit(const std::vector<Box>& boxes) {
  // A non-finite box becomes the empty one (never near anything).
  const Box empty{Vec3::Constant(std::numeric_limits<double>::infinity()),
                  Vec3::Constant(-std::numeric_limits<double>::infinity())};
  boxes_.resize(items_.size());
  for (std::size_t k = 0; k < items_.size(); ++k) {
    const Box& b = boxes[items_[k]];
    boxes_[k] = b.lo.allFinite() && b.hi.allFinite() ? b : empty;
  }
  // Children come after their parent: fit from the last node back.
  for (int i = static_cast<int>(nodes_.size()) - 1; i >= 0; --i) {
    Node& node = nodes_[i];
    if (node.left < 0) {
      Box b = boxes_[node.first];
      for (int k = node.first + 1; k < node.first + node.count; ++k) b = merge(b, boxes_[k]);
      node.box = b;
    } else {
      node.box = merge(nodes_[node.left].box, nodes_[node.right].box);
    }
  }
}

}  // namespace layers::sim::detail
