// garment_untangle.cpp -- smoothing a garment where it crosses itself
// (see garment_untangle.h).
#include "layers/garment/garment_untangle.h"

#include <algorithm>
#include <map>
#include <utility>

#include "layers/geometry/intersect.h"

namespace layers::garment {

std::int64_t untangle(geometry::Points& v, const geometry::Faces& faces, const std::vector<std::uint8_t>& boundary,
                      const std::function<void()>& push_out) {
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(v.rows()));
  std::map<std::pair<int, int>, int> uses;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      neighbours[a].push_back(b);
      neighbours[b].push_back(a);
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  // Neighbours along an opening: edges of one face between two opening
  // vertices.
  std::vector<std::vector<int>> along_opening(static_cast<std::size_t>(v.rows()));
  for (const auto& [edge, count] : uses) {
    if (count != 1 || !boundary[edge.first] || !boundary[edge.second]) continue;
    along_opening[edge.first].push_back(edge.second);
    along_opening[edge.second].push_back(edge.first);
  }
  std::int64_t pairs = 0;
  for (int round = 0; round < 2 * kUntangleRounds; ++round) {
    const geometry::TriMesh mesh{v, faces};
    const geometry::MeshCrossings c = geometry::self_crossings(geometry::FaceTree(mesh));
    pairs = c.pairs;
    if (pairs == 0) break;
    const bool openings_move = round >= kUntangleRounds;
    const std::vector<char> region = geometry::grow_faces(mesh, c.a_faces, 2);
    std::vector<char> moving(static_cast<std::size_t>(v.rows()), 0);
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
      if (region[f])
        for (int k = 0; k < 3; ++k) moving[faces(f, k)] = openings_move || !boundary[faces(f, k)];
    for (int sweep = 0; sweep < 3; ++sweep) {
      const geometry::Points before = v;
      for (Eigen::Index i = 0; i < v.rows(); ++i) {
        // An opening vertex moves along the opening, between its two
        // neighbours there (fewer: an end or a flag off any opening, kept).
        const std::vector<int>& around = boundary[i] ? along_opening[i] : neighbours[i];
        if (!moving[i] || around.size() < (boundary[i] ? 2u : 1u)) continue;
        Eigen::RowVector3f mean = Eigen::RowVector3f::Zero();
        for (int j : around) mean += before.row(j);
        v.row(i) = mean / static_cast<float>(around.size());
      }
    }
    push_out();
  }
  if (pairs > 0) pairs = geometry::self_crossings(geometry::FaceTree(geometry::TriMesh{v, faces})).pairs;
  return pairs;
}

}  // namespace layers::garment
