// garment_untangle.cpp -- smoothing a garment where it crosses itself
// (see garment_untangle.h).
#include "layers/garment/garment_untangle.h"

#include "layers/geometry/intersect.h"
#include "layers/geometry/topology.h"

namespace layers::garment {

std::int64_t untangle(geometry::Points& v, const geometry::Faces& faces, const std::vector<std::uint8_t>& boundary,
                      const std::function<void()>& push_out) {
  // Built at the first crossing: most garments have none.
  std::vector<std::vector<int>> neighbours, along_opening;
  const auto build_neighbours = [&] {
    neighbours.resize(static_cast<std::size_t>(v.rows()));
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int a = faces(f, k), b = faces(f, (k + 1) % 3);
        neighbours[a].push_back(b);
        neighbours[b].push_back(a);
      }
    // Along an opening: boundary edges between two opening vertices.
    along_opening.resize(neighbours.size());
    const geometry::Edges open = geometry::boundary_edges(faces);
    for (Eigen::Index e = 0; e < open.rows(); ++e) {
      const int a = open(e, 0), b = open(e, 1);
      if (!boundary[a] || !boundary[b]) continue;
      along_opening[a].push_back(b);
      along_opening[b].push_back(a);
    }
  };
  std::int64_t pairs = 0;
  for (int round = 0;; ++round) {
    const geometry::TriMesh mesh{v, faces};
    const geometry::MeshCrossings c = geometry::self_crossings(geometry::FaceTree(mesh));
    pairs = c.pairs;
    if (pairs == 0 || round == 2 * kUntangleRounds) break;
    if (neighbours.empty()) build_neighbours();
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
  return pairs;
}

}  // namespace layers::garment
