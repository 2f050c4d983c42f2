// Where a refused scene's frame broke: stretched edges, crossings (see refused_where.h).
#include "refused_where.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "layers/generate/stored_measures.h"
#include "layers/geometry/intersect.h"
#include "layers/geometry/pinch.h"

namespace layers::generate {

namespace {

struct Edge {
  double stretch;
  std::size_t garment;
  int a, b;
};

// Every edge of every garment of a stored frame with its stretch (length
// over rest length - 1; edges of no rest length left out).
std::vector<Edge> stretched_edges(const StoredFrame& f) {
  std::vector<Edge> edges;
  for (std::size_t g = 0; g < f.garments.size(); ++g) {
    const sim::MeasuredGarment& m = f.garments[g];
    for (Eigen::Index e = 0; e < m.edges.rows(); ++e) {
      if (!(m.rest_lengths[e] > 0)) continue;
      const int u = m.edges(e, 0), v = m.edges(e, 1);
      const double length = (m.positions.row(u).cast<double>() - m.positions.row(v).cast<double>()).norm();
      edges.push_back({length / m.rest_lengths[e] - 1.0, g, std::min(u, v), std::max(u, v)});
    }
  }
  return edges;
}

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
  if (frame < 0 || frame >= seq.n_frames) return out;
  const StoredFrame f = stored_frame(seq, frame);
  std::vector<geometry::TriMesh> garments;
  for (const sim::MeasuredGarment& g : f.garments) garments.push_back({g.positions, g.faces});
  if (f.body.num_faces() > 0) {
    const geometry::FaceTree tree(f.body);
    const geometry::MeshCrossings self = geometry::self_crossings(tree);
    const geometry::PinchZones zones = geometry::pinch_zones_under(
        f.body, self.pairs > 0 ? self.a_faces : std::vector<char>{}, pinch_distance, garments);
    for (std::size_t g = 0; g < garments.size(); ++g) {
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
  int best = 0;
  double worst = -1e30;
  for_each_stored_frame(seq, [&](std::int64_t t, const StoredFrame& f) {
    for (const Edge& e : stretched_edges(f))
      if (e.stretch > worst) worst = e.stretch, best = static_cast<int>(t);
  });
  return best;
}

std::vector<std::string> most_stretched_edges(const data::SequenceData& seq, int frame, int count) {
  if (frame < 0 || frame >= seq.n_frames) return {};
  const StoredFrame f = stored_frame(seq, frame);
  std::vector<Edge> edges = stretched_edges(f);
  const std::size_t keep = std::min(edges.size(), static_cast<std::size_t>(std::max(count, 0)));
  std::partial_sort(edges.begin(), edges.begin() + static_cast<std::ptrdiff_t>(keep), edges.end(),
                    [](const Edge& x, const Edge& y) { return x.stretch > y.stretch; });
  std::vector<std::string> out;
  for (std::size_t i = 0; i < keep; ++i) {
    const Edge& e = edges[i];
    const geometry::Points& p = f.garments[e.garment].positions;
    const Eigen::Vector3d mid = 0.5 * (p.row(e.a).cast<double>() + p.row(e.b).cast<double>()).transpose();
    const std::string joint = nearest_joint(seq, frame, mid);
    char line[256];
    std::snprintf(line, sizeof line, "%s: edge %d-%d stretched %.2f%% at (%.3f, %.3f, %.3f) m, nearest joint %s",
                  seq.garments[e.garment].name.c_str(), e.a, e.b, 100.0 * e.stretch, mid.x(), mid.y(), mid.z(),
                  joint.c_str());
    out.emplace_back(line);
  }
  return out;
}

}  // namespace layers::generate
