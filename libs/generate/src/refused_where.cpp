// Where a refused scene's frame broke: stretched edges, crossings (see refused_where.h).
#include "refused_where.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <utility>

#include "layers/geometry/intersect.h"
#include "layers/geometry/pinch.h"

namespace layers::generate {

namespace {

struct Edge {
  double stretch;
  std::size_t garment;
  int a, b;
};

std::vector<Edge> stretched_edges(const data::SequenceData& seq, int frame) {
  std::vector<Edge> edges;
  for (std::size_t g = 0; g < seq.garments.size(); ++g) {
    const data::GarmentData& garment = seq.garments[g];
    const std::size_t nv = static_cast<std::size_t>(garment.n_vertices());
    if (garment.positions.size() < (static_cast<std::size_t>(frame) + 1) * nv * 3) continue;
    const float* p = garment.positions.data() + static_cast<std::size_t>(frame) * nv * 3;
    std::set<std::pair<int, int>> seen;
    for (std::size_t f = 0; f + 2 < garment.faces.size(); f += 3)
      for (int k = 0; k < 3; ++k) {
        const int u = garment.faces[f + k], v = garment.faces[f + (k + 1) % 3];
        if (!seen.emplace(std::min(u, v), std::max(u, v)).second) continue;
        const auto at = [](const float* x, int i) { return Eigen::Vector3d(x[3 * i], x[3 * i + 1], x[3 * i + 2]); };
        const double rest = (at(garment.rest.data(), u) - at(garment.rest.data(), v)).norm();
        if (!(rest > 0)) continue;
        edges.push_back({(at(p, u) - at(p, v)).norm() / rest - 1.0, g, std::min(u, v), std::max(u, v)});
      }
  }
  return edges;
}

Eigen::Vector3d point(const float* x, int i) { return {x[3 * i], x[3 * i + 1], x[3 * i + 2]}; }

// The name of the body joint nearest to `p` in frame `frame` ("none"
// without joints).
std::string nearest_joint(const data::SequenceData& seq, int frame, const Eigen::Vector3d& p) {
  const std::size_t nj = seq.body.joint_names.size();
  std::string joint = "none";
  double best = 1e30;
  if (seq.body.joints.size() < (static_cast<std::size_t>(frame) + 1) * nj * 12) return joint;
  const float* m = seq.body.joints.data() + static_cast<std::size_t>(frame) * nj * 12;
  for (std::size_t j = 0; j < nj; ++j) {
    const Eigen::Vector3d t(m[j * 12 + 3], m[j * 12 + 7], m[j * 12 + 11]);
    if ((t - p).norm() < best) best = (t - p).norm(), joint = seq.body.joint_names[j];
  }
  return joint;
}

// A garment's mesh in frame `frame` (empty when the frame is not stored).
geometry::TriMesh garment_mesh(const data::GarmentData& g, int frame) {
  geometry::TriMesh m;
  const std::size_t nv = static_cast<std::size_t>(g.n_vertices());
  if (g.positions.size() < (static_cast<std::size_t>(frame) + 1) * nv * 3) return m;
  m.vertices = Eigen::Map<const geometry::Points>(g.positions.data() + static_cast<std::size_t>(frame) * nv * 3,
                                                  static_cast<Eigen::Index>(nv), 3);
  m.faces = Eigen::Map<const geometry::Faces>(g.faces.data(), static_cast<Eigen::Index>(g.n_faces()), 3);
  return m;
}

// "<what>: N faces, near J n at (x, y, z) m, ..." for the flagged faces of `mesh`.
std::string place_line(const data::SequenceData& seq, int frame, const std::string& what, const geometry::TriMesh& mesh,
                       const std::vector<char>& faces, int count) {
  struct Group {
    int faces = 0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  };
  std::map<std::string, Group> groups;
  int total = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (!faces[f]) continue;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) c += mesh.vertices.row(mesh.faces(f, k)).cast<double>().transpose() / 3.0;
    Group& g = groups[nearest_joint(seq, frame, c)];
    ++g.faces;
    g.sum += c;
    ++total;
  }
  std::vector<std::pair<std::string, Group>> order(groups.begin(), groups.end());
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.second.faces > b.second.faces; });
  std::string line = what + ": " + std::to_string(total) + (total == 1 ? " face" : " faces");
  for (std::size_t i = 0; i < order.size() && i < static_cast<std::size_t>(std::max(count, 0)); ++i) {
    const Eigen::Vector3d c = order[i].second.sum / order[i].second.faces;
    char part[160];
    std::snprintf(part, sizeof part, "%s near %s %d at (%.3f, %.3f, %.3f) m", i == 0 ? "," : ";",
                  order[i].first.c_str(), order[i].second.faces, c.x(), c.y(), c.z());
    line += part;
  }
  return line;
}

}  // namespace

std::vector<std::string> crossing_places(const data::SequenceData& seq, int frame, double pinch_distance, int count) {
  std::vector<std::string> out;
  std::vector<geometry::TriMesh> garments;
  for (const data::GarmentData& g : seq.garments) garments.push_back(garment_mesh(g, frame));
  const std::size_t nb = static_cast<std::size_t>(seq.body.n_vertices());
  if (seq.body.positions.size() >= (static_cast<std::size_t>(frame) + 1) * nb * 3 && nb > 0) {
    geometry::TriMesh body;
    body.vertices = Eigen::Map<const geometry::Points>(
        seq.body.positions.data() + static_cast<std::size_t>(frame) * nb * 3, static_cast<Eigen::Index>(nb), 3);
    body.faces =
        Eigen::Map<const geometry::Faces>(seq.body.faces.data(), static_cast<Eigen::Index>(seq.body.n_faces()), 3);
    const geometry::FaceTree tree(body);
    const geometry::MeshCrossings self = geometry::self_crossings(tree);
    double longest = 0;
    Eigen::Index rows = 0;
    for (const geometry::TriMesh& m : garments) rows += m.num_vertices();
    geometry::Points cloth(rows, 3);
    rows = 0;
    for (const geometry::TriMesh& m : garments) {
      if (m.num_vertices() == 0) continue;
      cloth.middleRows(rows, m.num_vertices()) = m.vertices;
      rows += m.num_vertices();
      for (int f = 0; f < m.num_faces(); ++f)
        for (int k = 0; k < 3; ++k)
          longest = std::max(
              longest,
              static_cast<double>((m.vertices.row(m.faces(f, k)) - m.vertices.row(m.faces(f, (k + 1) % 3))).norm()));
    }
    const geometry::PinchZones zones = geometry::pinch_zones_under(
        body, self.pairs > 0 ? self.a_faces : std::vector<char>{}, pinch_distance, cloth, longest);
    for (std::size_t g = 0; g < garments.size(); ++g) {
      if (garments[g].num_faces() == 0) continue;
      std::vector<char> through(static_cast<std::size_t>(garments[g].num_faces()), 0);
      bool any = false;
      geometry::visit_crossings(garments[g], tree, [&](int a, int b) {
        if (zones.faces[b]) return;
        through[a] = 1;
        any = true;
      });
      if (any)
        out.push_back(place_line(seq, frame, seq.garments[g].name + " through the body", garments[g], through, count));
    }
  }
  for (std::size_t a = 0; a < garments.size(); ++a)
    for (std::size_t b = 0; b < garments.size(); ++b) {
      if (a == b || garments[a].num_faces() == 0 || garments[b].num_faces() == 0) continue;
      const geometry::MeshCrossings c = geometry::crossings(garments[a], geometry::FaceTree(garments[b]));
      if (c.pairs == 0) continue;
      out.push_back(place_line(seq, frame, seq.garments[a].name + " through " + seq.garments[b].name, garments[a],
                               c.a_faces, count));
    }
  return out;
}

int most_stretched_frame(const data::SequenceData& seq) {
  const int frames = static_cast<int>(seq.wind.strength.size());
  int best = 0;
  double worst = -1e30;
  for (int f = 0; f < frames; ++f)
    for (const Edge& e : stretched_edges(seq, f))
      if (e.stretch > worst) worst = e.stretch, best = f;
  return best;
}

std::vector<std::string> most_stretched_edges(const data::SequenceData& seq, int frame, int count) {
  std::vector<Edge> edges = stretched_edges(seq, frame);
  const std::size_t keep = std::min(edges.size(), static_cast<std::size_t>(std::max(count, 0)));
  std::partial_sort(edges.begin(), edges.begin() + static_cast<std::ptrdiff_t>(keep), edges.end(),
                    [](const Edge& x, const Edge& y) { return x.stretch > y.stretch; });
  std::vector<std::string> out;
  for (std::size_t i = 0; i < keep; ++i) {
    const Edge& e = edges[i];
    const data::GarmentData& garment = seq.garments[e.garment];
    const float* p = garment.positions.data() + static_cast<std::size_t>(frame) * garment.n_vertices() * 3;
    const Eigen::Vector3d mid = 0.5 * (Eigen::Vector3d(p[3 * e.a], p[3 * e.a + 1], p[3 * e.a + 2]) +
                                       Eigen::Vector3d(p[3 * e.b], p[3 * e.b + 1], p[3 * e.b + 2]));
    const std::string joint = nearest_joint(seq, frame, mid);
    char line[256];
    std::snprintf(line, sizeof line, "%s: edge %d-%d stretched %.2f%% at (%.3f, %.3f, %.3f) m, nearest joint %s",
                  garment.name.c_str(), e.a, e.b, 100.0 * e.stretch, mid.x(), mid.y(), mid.z(), joint.c_str());
    out.emplace_back(line);
  }
  return out;
}

}  // namespace layers::generate
