// The continuous-collision safety pass (see collision_pass.h).
#include "collision_pass.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <Eigen/Dense>

namespace layers::sim::detail {

namespace {

Box swept_box(const Vec3s& x0, const Vec3s& x1, const int* v, int n, double grow) {
  Box b{x0[v[0]], x0[v[0]]};
  for (int k = 0; k < n; ++k) {
    b.lo = b.lo.cwiseMin(x0[v[k]]).cwiseMin(x1[v[k]]);
    b.hi = b.hi.cwiseMax(x0[v[k]]).cwiseMax(x1[v[k]]);
  }
  b.lo.array() -= grow;
  b.hi.array() += grow;
  return b;
}

}  // namespace

bool CollisionPass::starts_inside(const std::array<int, 4>& v, bool edge_edge) const {
  const auto body = [&](int i) { return layout_->owner[i] < 0; };
  if (edge_edge) {
    // Cloth edge first, body edge second (see detect()).
    double s = 0, t = 0;
    segment_segment_distance2(x0_[v[0]], x0_[v[1]], x0_[v[2]], x0_[v[3]], &s, &t);
    const Vec3 d = (1 - s) * x0_[v[0]] + s * x0_[v[1]] - ((1 - t) * x0_[v[2]] + t * x0_[v[3]]);
    const Vec3 out = body_normals_[v[2] - layout_->cloth_vertices] + body_normals_[v[3] - layout_->cloth_vertices];
    return d.dot(out) < 0;
  }
  if (body(v[1])) {
    // Cloth vertex on the inside of a body face: behind its plane where its
    // closest point is inside the face, by the body's vertex normals
    // (interpolated) where it is on the face's rim (behind the plane
    // alone is not inside near a convex edge: the vertex could slip
    // through the face from there).
    std::array<double, 3> b;
    point_triangle_distance2(x0_[v[0]], x0_[v[1]], x0_[v[2]], x0_[v[3]], &b);
    const Vec3 c = b[0] * x0_[v[1]] + b[1] * x0_[v[2]] + b[2] * x0_[v[3]];
    constexpr double kRim = 1e-9;
    Vec3 n = (x0_[v[2]] - x0_[v[1]]).cross(x0_[v[3]] - x0_[v[1]]);
    if (b[0] <= kRim || b[1] <= kRim || b[2] <= kRim) {
      n = Vec3::Zero();
      for (int k = 0; k < 3; ++k) n += b[k] * body_normals_[v[1 + k] - layout_->cloth_vertices];
    }
    return (x0_[v[0]] - c).dot(n) < 0;
  }
  // Body vertex whose closest cloth point lies on the body's inside.
  std::array<double, 3> b;
  point_triangle_distance2(x0_[v[0]], x0_[v[1]], x0_[v[2]], x0_[v[3]], &b);
  const Vec3 c = b[0] * x0_[v[1]] + b[1] * x0_[v[2]] + b[2] * x0_[v[3]];
  return (c - x0_[v[0]]).dot(body_normals_[v[0] - layout_->cloth_vertices]) < 0;
}

bool CollisionPass::test(const std::array<int, 4>& v, bool edge_edge, double gap, std::vector<Hit>& hits) const {
  Sweep sweep;
  sweep.edge_edge = edge_edge;
  for (int k = 0; k < 4; ++k) {
    sweep.x0[k] = x0_[v[k]];
    sweep.dx[k] = x1_[v[k]] - x0_[v[k]];
  }
  double toi = 0;
  if (!sweep_hits(sweep, gap, toi)) return false;
  if ((layout_->owner[v[0]] < 0 || layout_->owner[v[3]] < 0) && starts_inside(v, edge_edge)) return false;
  hits.push_back({v, edge_edge, toi});
  return true;
}

void CollisionPass::detect(double gap, std::vector<Hit>& hits, bool incremental) {
  const ContactLayout& L = *layout_;
  std::vector<Hit> kept;
  if (incremental) {
    for (const Hit& h : hits)
      if (!touched(h.v.data(), 4)) kept.push_back(h);
  }
  hits.swap(kept);
  // The candidates hold every pair that can come within the gap while the
  // cloth stays in its bounds: made again only when it left them.
  candidates_->ensure(
      L, [&](int g) -> const Vec3& { return x0_[g]; }, [&](int g) -> const Vec3& { return x1_[g]; }, sweep_);
  const double grow = 0.5 * gap;
  // The swept boxes of the features to test (all of them, or, when
  // incremental, those with a moved vertex), and which features moved.
  vertex_boxes_.resize(static_cast<std::size_t>(L.cloth_vertices));
  edge_boxes_.resize(static_cast<std::size_t>(L.cloth_edges));
  face_boxes_.resize(static_cast<std::size_t>(L.cloth_faces));
  edge_moved_.assign(static_cast<std::size_t>(L.cloth_edges), incremental ? 0 : 1);
  face_moved_.assign(static_cast<std::size_t>(L.cloth_faces), incremental ? 0 : 1);
  for (int v = 0; v < L.cloth_vertices; ++v)
    if (!incremental || dirty_[v]) vertex_boxes_[v] = swept_box(x0_, x1_, &v, 1, grow);
  for (int e = 0; e < L.cloth_edges; ++e) {
    if (incremental && !touched(L.edges[e].data(), 2)) continue;
    edge_moved_[e] = 1;
    edge_boxes_[e] = swept_box(x0_, x1_, L.edges[e].data(), 2, grow);
  }
  for (int f = 0; f < L.cloth_faces; ++f) {
    if (incremental && !touched(L.faces[f].data(), 3)) continue;
    face_moved_[f] = 1;
    face_boxes_[f] = swept_box(x0_, x1_, L.faces[f].data(), 3, grow);
  }
  // A feature that did not move keeps the box it had (the positions it
  // was made from are unchanged).
  const auto moved = [&](int v) { return !incremental || dirty_[v] != 0; };
  // A cloth feature's sweep against a body feature's over the frame.
  const auto meets_body = [&](const Box& cloth, const Box& body) {
    return (cloth.lo.array() <= body.hi.array() + grow).all() && (body.lo.array() - grow <= cloth.hi.array()).all();
  };
  const int off = L.cloth_vertices;
  for (const auto& [v, f] : candidates_->cloth_vertex_face()) {
    if (!moved(v) && !face_moved_[f]) continue;
    const auto& t = L.faces[f];
    if (vertex_boxes_[v].overlaps(face_boxes_[f])) test({v, t[0], t[1], t[2]}, false, gap, hits);
  }
  for (const auto& p : candidates_->body_vertex_face()) {
    const auto [v, i] = p.ids;
    if (!moved(v) || !meets_body(vertex_boxes_[v], p.body)) continue;
    const auto& t = L.faces[L.cloth_faces + i];
    test({v, t[0], t[1], t[2]}, false, gap, hits);
  }
  for (const auto& p : candidates_->body_face_vertex()) {
    const auto [f, i] = p.ids;
    if (!face_moved_[f] || !meets_body(face_boxes_[f], p.body)) continue;
    const auto& t = L.faces[f];
    test({off + i, t[0], t[1], t[2]}, false, gap, hits);
  }
  for (const auto& [e, o] : candidates_->cloth_edge_edge_gap()) {
    if (!edge_moved_[e] && !edge_moved_[o]) continue;
    const auto& a = L.edges[e];
    const auto& b = L.edges[o];
    if (edge_boxes_[e].overlaps(edge_boxes_[o])) test({a[0], a[1], b[0], b[1]}, true, gap, hits);
  }
  for (const auto& p : candidates_->body_edge_edge_gap()) {
    const auto [e, i] = p.ids;
    if (!edge_moved_[e] || !meets_body(edge_boxes_[e], p.body)) continue;
    const auto& a = L.edges[e];
    const auto& c = L.edges[L.cloth_edges + i];
    test({a[0], a[1], c[0], c[1]}, true, gap, hits);
  }
}

bool CollisionPass::correct(const Hit& hit, double gap) {
  // A body pair in a pinch zone: the body yields there (pushing the cloth
  // out of one part pushes it into the other, and drags it).
  if (body_.pinch != nullptr && (layout_->owner[hit.v[0]] < 0 || layout_->owner[hit.v[3]] < 0)) {
    for (int v : hit.v)
      if (layout_->owner[v] < 0 && (*body_.pinch)[v - layout_->cloth_vertices]) return true;
  }
  // The pair where CCD stopped, and weights w with sum_k w_k x_k = the
  // vector between its closest points (first feature minus second).
  std::array<Vec3, 4> x;
  for (int k = 0; k < 4; ++k) x[k] = x0_[hit.v[k]] + hit.toi * (x1_[hit.v[k]] - x0_[hit.v[k]]);
  std::array<double, 4> w;
  Vec3 fallback;
  if (hit.edge_edge) {
    double s = 0, t = 0;
    segment_segment_distance2(x[0], x[1], x[2], x[3], &s, &t);
    w = {1 - s, s, -(1 - t), -t};
    fallback = (x[1] - x[0]).cross(x[3] - x[2]);
  } else {
    std::array<double, 3> b;
    point_triangle_distance2(x[0], x[1], x[2], x[3], &b);
    w = {1, -b[0], -b[1], -b[2]};
    fallback = (x[2] - x[1]).cross(x[3] - x[1]);
  }
  const auto combine = [&](const auto& pos) {
    Vec3 r = Vec3::Zero();
    for (int k = 0; k < 4; ++k) r += w[k] * pos(k);
    return r;
  };
  Vec3 n = combine([&](int k) { return x[k]; });
  double len = n.norm();
  if (!(len > 1e-12)) {
    // Touching: the features' own normal, on the side they started on.
    n = fallback;
    len = n.norm();
    if (!(len > 0)) {
      n = combine([&](int k) { return x0_[hit.v[k]]; });
      len = n.norm();
    }
    if (!(len > 0)) return false;
    if (n.dot(combine([&](int k) { return x0_[hit.v[k]]; })) < 0) n = -n;
  }
  n /= len;
  double denom = 0;
  std::array<double, 4> im;
  for (int k = 0; k < 4; ++k) {
    const int v = hit.v[k];
    im[k] = back_[v] ? 0.0 : inv_mass_[v];
    denom += w[k] * w[k] * im[k];
  }
  if (!(denom > 0)) return false;
  const double sep = combine([&](int k) { return x1_[hit.v[k]]; }).dot(n);
  const double j = 2 * gap - sep;
  if (j <= 0) return true;
  for (int k = 0; k < 4; ++k) {
    if (im[k] == 0.0) continue;
    x1_[hit.v[k]] += (j * w[k] * im[k] / denom) * n;
    dirty_[hit.v[k]] = 1;
  }
  return true;
}

CollisionPassStats CollisionPass::run(const std::vector<Cloth>& cloths, const std::vector<Cloth::State*>& states,
                                      const SweptBody& body, double gap, int rounds, std::vector<Vec3s>& pushes,
                                      std::vector<std::vector<std::uint8_t>>& reverted,
                                      const std::vector<std::vector<std::uint8_t>>* moved) {
  if (moved != nullptr) return resume(cloths, states, gap, rounds, pushes, reverted, *moved);
  layout_->update(cloths, body.faces, body.edges, body.start);
  ContactCandidates::Reach reach = candidates_->reach();
  reach.gap = gap;
  if (candidates_ == &own_candidates_) reach.margin = kDefaultMargin;
  candidates_->set_reach(reach);
  body_ = body;
  // The body's sweep over the frame (or this substep alone, made again at
  // every detection).
  const bool frame = body.frame_start != nullptr && body.frame_end != nullptr;
  sweep_ = {frame ? body.frame_start : body.start, frame ? body.frame_end : body.end, frame ? body.frame : -1};
  if (body.start == nullptr) sweep_ = {};
  const std::size_t total = layout_->owner.size();
  x0_.resize(total);
  x1_.resize(total);
  inv_mass_.resize(total);
  back_.assign(total, 0);
  dirty_.assign(total, 0);
  for (std::size_t c = 0; c < states.size(); ++c) {
    const Cloth::State& s = *states[c];
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      x0_[layout_->offset[c] + i] = s.x_start[i];
      x1_[layout_->offset[c] + i] = s.x[i];
      inv_mass_[layout_->offset[c] + i] = s.inv_mass[i];
    }
  }
  for (int i = 0; i < layout_->body_vertices; ++i) {
    x0_[layout_->cloth_vertices + i] = (*body.start)[i];
    x1_[layout_->cloth_vertices + i] = (*body.end)[i];
    inv_mass_[layout_->cloth_vertices + i] = 0.0;
  }
  // The body's vertex normals at the start (for starts_inside()).
  body_normals_.assign(static_cast<std::size_t>(std::max(layout_->body_vertices, 0)), Vec3::Zero());
  for (int f = layout_->cloth_faces; f < static_cast<int>(layout_->faces.size()); ++f) {
    const auto& t = layout_->faces[f];
    const Vec3 n = (x0_[t[1]] - x0_[t[0]]).cross(x0_[t[2]] - x0_[t[0]]);
    for (int k = 0; k < 3; ++k) body_normals_[t[k] - layout_->cloth_vertices] += n;
  }
  hits_.clear();
  detect(gap, hits_, false);
  return resolve(states, gap, rounds, pushes, reverted);
}

CollisionPassStats CollisionPass::resume(const std::vector<Cloth>& cloths, const std::vector<Cloth::State*>& states,
                                         double gap, int rounds, std::vector<Vec3s>& pushes,
                                         std::vector<std::vector<std::uint8_t>>& reverted,
                                         const std::vector<std::vector<std::uint8_t>>& moved) {
  (void)cloths;
  for (std::size_t c = 0; c < states.size(); ++c) {
    const Cloth::State& s = *states[c];
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!moved[c][i]) continue;
      const int g = layout_->offset[c] + static_cast<int>(i);
      x1_[g] = s.x[i];
      dirty_[g] = 1;
      if (back_[g] && x1_[g] != x0_[g]) back_[g] = 0;
    }
  }
  detect(gap, hits_, true);
  std::fill(dirty_.begin(), dirty_.end(), 0);
  return resolve(states, gap, rounds, pushes, reverted);
}

template <class Find>
void CollisionPass::move_zones(std::vector<int>& parent, Find&& find, CollisionPassStats& stats) {
  // Per zone root: mass, mass-weighted start and end sums.
  struct Zone {
    double mass = 0;
    Vec3 c0 = Vec3::Zero(), c1 = Vec3::Zero();
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    Vec3 spin = Vec3::Zero();
    bool pinned = false;
  };
  std::vector<int> members;
  for (int v = 0; v < layout_->cloth_vertices; ++v)
    if (parent[v] >= 0) members.push_back(v);
  std::unordered_map<int, Zone> zones;
  for (int v : members) {
    Zone& z = zones[find(v)];
    if (inv_mass_[v] == 0.0 || back_[v]) {
      z.pinned = true;
      continue;
    }
    const double m = 1.0 / inv_mass_[v];
    z.mass += m;
    z.c0 += m * x0_[v];
    z.c1 += m * x1_[v];
  }
  for (auto& [root, z] : zones) {
    if (z.mass > 0) {
      z.c0 /= z.mass;
      z.c1 /= z.mass;
    }
  }
  for (int v : members) {
    Zone& z = zones[find(v)];
    if (z.pinned) continue;
    const double m = 1.0 / inv_mass_[v];
    const Vec3 r = x0_[v] - z.c0, u = (x1_[v] - x0_[v]) - (z.c1 - z.c0);
    z.spin += m * r.cross(u);
    z.inertia += m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  std::unordered_map<int, Eigen::Matrix3d> rotation;
  for (auto& [root, z] : zones) {
    if (z.pinned || z.mass <= 0) continue;
    // Angular velocity (per substep) from the spin; a degenerate zone (a
    // line of vertices) keeps only the spin its inertia can carry.
    const Vec3 w = z.inertia.completeOrthogonalDecomposition().solve(z.spin);
    const double angle = w.norm();
    rotation[root] =
        angle > 1e-12 ? Eigen::AngleAxisd(angle, w / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
  }
  for (int v : members) {
    const int root = find(v);
    const Zone& z = zones[root];
    if (z.pinned || z.mass <= 0) continue;  // left to the fail-safe below
    const Vec3 moved = z.c1 + rotation[root] * (x0_[v] - z.c0);
    if (moved != x1_[v]) {
      x1_[v] = moved;
      dirty_[v] = 1;
    }
    ++stats.zoned;
  }
}

CollisionPassStats CollisionPass::resolve(const std::vector<Cloth::State*>& states, double gap, int rounds,
                                          std::vector<Vec3s>& pushes,
                                          std::vector<std::vector<std::uint8_t>>& reverted) {
  CollisionPassStats stats;
  std::vector<Hit>& hits = hits_;
  const auto again = [&] {
    detect(gap, hits, true);
    std::fill(dirty_.begin(), dirty_.end(), 0);
  };
  stats.pairs = static_cast<long>(hits.size());
  while (!hits.empty() && stats.rounds < rounds) {
    for (const Hit& h : hits) correct(h, gap);
    ++stats.rounds;
    again();
  }
  // Impact zones: the cloth vertices of cloth-cloth pairs still failing,
  // merged (union-find) with every zone they touch, each moved rigidly
  // with its mass's mean motion and spin (Harmon et al. 2008), which keeps
  // a zone's own pairs as far apart as they started; zones grow while new
  // pairs fail, for at most kZoneRounds rounds.
  const auto with_body = [&](const Hit& h) { return layout_->owner[h.v[0]] < 0 || layout_->owner[h.v[3]] < 0; };
  std::vector<int> parent;
  for (int round = 0; round < kZoneRounds; ++round) {
    bool any = false;
    for (const Hit& h : hits) any = any || !with_body(h);
    if (!any) break;
    if (parent.empty()) {
      parent.resize(static_cast<std::size_t>(layout_->cloth_vertices));
      for (int v = 0; v < layout_->cloth_vertices; ++v) parent[v] = -1;  // -1: in no zone
    }
    const auto find = [&](int v) {
      while (parent[v] != v) v = parent[v] = parent[parent[v]];
      return v;
    };
    for (const Hit& h : hits) {
      if (with_body(h)) continue;
      for (int v : h.v)
        if (parent[v] < 0) parent[v] = v;
      for (int k = 1; k < 4; ++k) {
        const int a = find(h.v[0]), b = find(h.v[k]);
        if (a != b) parent[b] = a;
      }
    }
    move_zones(parent, find, stats);
    again();
  }

  // Fail-safe: undo the substep's motion of every cloth vertex of a
  // cloth-cloth pair still failing, until those pairs have no cloth vertex
  // that moves. Body pairs never stop cloth (stopped cloth in front of a
  // moving limb is swept through and torn): where they still fail, the
  // body yields, and they are counted.
  while (!hits.empty()) {
    bool changed = false;
    for (const Hit& h : hits) {
      if (with_body(h)) continue;
      for (int v : h.v) {
        if (back_[v] || inv_mass_[v] == 0.0) continue;
        x1_[v] = x0_[v];
        back_[v] = 1;
        dirty_[v] = 1;
        changed = true;
        ++stats.reverted;
      }
    }
    if (!changed) break;
    again();
  }
  stats.yielded = static_cast<long>(std::count_if(hits.begin(), hits.end(), with_body));

  for (std::size_t c = 0; c < states.size(); ++c) {
    Cloth::State& s = *states[c];
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      const int g = layout_->offset[c] + static_cast<int>(i);
      pushes[c][i] += x1_[g] - s.x[i];
      s.x[i] = x1_[g];
      reverted[c][i] = back_[g];
    }
  }
  return stats;
}

}  // namespace layers::sim::detail
