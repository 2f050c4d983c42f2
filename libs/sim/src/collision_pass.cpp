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

bool shares_vertex(const int* a, int na, const int* b, int nb) {
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nb; ++j)
      if (a[i] == b[j]) return true;
  return false;
}

}  // namespace

void CollisionPass::layout(const std::vector<Cloth>& cloths, const SweptBody& body) {
  std::vector<long> revisions;
  for (const Cloth& c : cloths) revisions.push_back(c.revision());
  const int nb = body.start != nullptr ? static_cast<int>(body.start->size()) : 0;
  if (revisions == revisions_ && body.faces == body_faces_ && body.edges == body_edges_ && nb == body_vertices_) return;
  revisions_ = revisions;
  body_faces_ = body.faces;
  body_edges_ = body.edges;
  body_vertices_ = nb;
  offset_.clear();
  edge_offset_.clear();
  face_offset_.clear();
  owner_.clear();
  self_.clear();
  edges_.clear();
  faces_.clear();
  double length = 0;
  long count = 0;
  for (std::size_t c = 0; c < cloths.size(); ++c) {
    const Cloth& cloth = cloths[c];
    const int off = static_cast<int>(owner_.size());
    offset_.push_back(off);
    edge_offset_.push_back(static_cast<int>(edges_.size()));
    face_offset_.push_back(static_cast<int>(faces_.size()));
    owner_.insert(owner_.end(), static_cast<std::size_t>(cloth.num_vertices()), static_cast<int>(c));
    self_.push_back(cloth.self_contact() ? 1 : 0);
    const geometry::Edges& e = cloth.edges();
    for (Eigen::Index k = 0; k < e.rows(); ++k) edges_.push_back({off + e(k, 0), off + e(k, 1)});
    for (const auto& f : cloth.topology().faces) faces_.push_back({off + f[0], off + f[1], off + f[2]});
    length += cloth.rest_lengths().sum();
    count += cloth.rest_lengths().size();
  }
  cloth_vertices_ = static_cast<int>(owner_.size());
  cloth_edges_ = static_cast<int>(edges_.size());
  cloth_faces_ = static_cast<int>(faces_.size());
  offset_.push_back(cloth_vertices_);
  edge_offset_.push_back(cloth_edges_);
  face_offset_.push_back(cloth_faces_);
  vertex_grids_.resize(cloths.size());
  edge_grids_.resize(cloths.size());
  face_grids_.resize(cloths.size());
  owner_.insert(owner_.end(), static_cast<std::size_t>(nb), -1);
  if (nb > 0 && body.faces != nullptr && body.edges != nullptr) {
    const int off = cloth_vertices_;
    for (Eigen::Index k = 0; k < body.edges->rows(); ++k)
      edges_.push_back({off + (*body.edges)(k, 0), off + (*body.edges)(k, 1)});
    for (const auto& f : *body.faces) faces_.push_back({off + f[0], off + f[1], off + f[2]});
  }
  // Cells about one mean edge long: a feature's swept box overlaps a few.
  cell_ = count > 0 ? std::max(length / count, 1e-4) : 0.01;
  // The body's grids: cells two mean body edges long (a cloth feature's
  // query then meets few body features per cell).
  body_cell_ = cell_;
  if (nb > 0 && body.edges != nullptr && body.edges->rows() > 0) {
    double sum = 0;
    for (Eigen::Index k = 0; k < body.edges->rows(); ++k)
      sum += ((*body.start)[(*body.edges)(k, 0)] - (*body.start)[(*body.edges)(k, 1)]).norm();
    body_cell_ = std::max(std::min(cell_, 2 * sum / static_cast<double>(body.edges->rows())), 1e-4);
  }
}

bool CollisionPass::starts_inside(const std::array<int, 4>& v, bool edge_edge) const {
  const auto body = [&](int i) { return owner_[i] < 0; };
  if (edge_edge) {
    // Cloth edge first, body edge second (see detect()).
    double s = 0, t = 0;
    segment_segment_distance2(x0_[v[0]], x0_[v[1]], x0_[v[2]], x0_[v[3]], &s, &t);
    const Vec3 d = (1 - s) * x0_[v[0]] + s * x0_[v[1]] - ((1 - t) * x0_[v[2]] + t * x0_[v[3]]);
    const Vec3 out = body_normals_[v[2] - cloth_vertices_] + body_normals_[v[3] - cloth_vertices_];
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
      for (int k = 0; k < 3; ++k) n += b[k] * body_normals_[v[1 + k] - cloth_vertices_];
    }
    return (x0_[v[0]] - c).dot(n) < 0;
  }
  // Body vertex whose closest cloth point lies on the body's inside.
  std::array<double, 3> b;
  point_triangle_distance2(x0_[v[0]], x0_[v[1]], x0_[v[2]], x0_[v[3]], &b);
  const Vec3 c = b[0] * x0_[v[1]] + b[1] * x0_[v[2]] + b[2] * x0_[v[3]];
  return (c - x0_[v[0]]).dot(body_normals_[v[0] - cloth_vertices_]) < 0;
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
  if ((owner_[v[0]] < 0 || owner_[v[3]] < 0) && starts_inside(v, edge_edge)) return false;
  hits.push_back({v, edge_edge, toi});
  return true;
}

void CollisionPass::detect(double gap, std::vector<Hit>& hits, bool incremental) {
  std::vector<Hit> kept;
  if (incremental) {
    for (const Hit& h : hits)
      if (!touched(h.v.data(), 4)) kept.push_back(h);
  }
  hits.swap(kept);
  const double grow = 0.5 * gap;
  vertex_boxes_.resize(static_cast<std::size_t>(cloth_vertices_));
  edge_boxes_.resize(static_cast<std::size_t>(cloth_edges_));
  face_boxes_.resize(static_cast<std::size_t>(cloth_faces_));
  for (int v = 0; v < cloth_vertices_; ++v) vertex_boxes_[v] = swept_box(x0_, x1_, &v, 1, grow);
  for (int e = 0; e < cloth_edges_; ++e) edge_boxes_[e] = swept_box(x0_, x1_, edges_[e].data(), 2, grow);
  for (int f = 0; f < cloth_faces_; ++f) face_boxes_[f] = swept_box(x0_, x1_, faces_[f].data(), 3, grow);
  // One grid per cloth: a cloth without self-contact never meets its own
  // features.
  const int nc = static_cast<int>(self_.size());
  for (int c = 0; c < nc; ++c) {
    vertex_grids_[c].build(vertex_boxes_, cell_, offset_[c], offset_[c + 1] - offset_[c]);
    edge_grids_[c].build(edge_boxes_, cell_, edge_offset_[c], edge_offset_[c + 1] - edge_offset_[c]);
    face_grids_[c].build(face_boxes_, cell_, face_offset_[c], face_offset_[c + 1] - face_offset_[c]);
  }
  // The cloths a feature of cloth c can meet.
  const auto partners = [&](int c, auto&& f) {
    for (int d = 0; d < nc; ++d)
      if (d != c || self_[c]) f(d);
  };
  // Which features to query, and which pairs to test: everything, or (when
  // incremental) the features with a moved vertex, each pair once.
  const auto moved = [&](const int* v, int n) { return !incremental || touched(v, n); };

  // The body's grids cover the region the cloths sweep (grown by a
  // margin); a moved feature outside it has the body filed again.
  const bool body = static_cast<int>(x0_.size()) > cloth_vertices_;
  if (body) {
    Box region{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
    for (const Box& b : vertex_boxes_) {
      region.lo = region.lo.cwiseMin(b.lo);
      region.hi = region.hi.cwiseMax(b.hi);
    }
    const bool inside =
        (region.lo.array() >= body_region_.lo.array()).all() && (region.hi.array() <= body_region_.hi.array()).all();
    if (!inside || body_.frame != body_frame_ || body_.frame < 0) {
      region.lo.array() -= 2 * cell_;
      region.hi.array() += 2 * cell_;
      file_body(gap, region, body_);
    }
  }
  const int off = cloth_vertices_;

  // Cloth vertices against cloth faces.
  for (int v = 0; v < cloth_vertices_; ++v) {
    if (!moved(&v, 1)) continue;
    partners(owner_[v], [&](int d) {
      face_grids_[d].visit(vertex_boxes_[v], [&](int f) {
        const auto& t = faces_[f];
        if (t[0] == v || t[1] == v || t[2] == v) return;
        test({v, t[0], t[1], t[2]}, false, gap, hits);
      });
    });
    if (!body) continue;
    body_face_grid_.visit(vertex_boxes_[v], [&](int f) {
      const auto& t = faces_[cloth_faces_ + f];
      test({v, t[0], t[1], t[2]}, false, gap, hits);
    });
  }
  for (int f = 0; f < cloth_faces_; ++f) {
    const auto& t = faces_[f];
    if (!moved(t.data(), 3)) continue;
    // Moved faces against the cloth vertices that did not move ...
    if (incremental) {
      partners(owner_[t[0]], [&](int d) {
        vertex_grids_[d].visit(face_boxes_[f], [&](int v) {
          if (dirty_[v] || t[0] == v || t[1] == v || t[2] == v) return;
          test({v, t[0], t[1], t[2]}, false, gap, hits);
        });
      });
    }
    // ... and against the body's vertices.
    if (body)
      body_vertex_grid_.visit(face_boxes_[f], [&](int i) { test({off + i, t[0], t[1], t[2]}, false, gap, hits); });
  }
  // Cloth edges against cloth edges (each pair once).
  for (int e = 0; e < cloth_edges_; ++e) {
    const auto& a = edges_[e];
    if (!moved(a.data(), 2)) continue;
    partners(owner_[a[0]], [&](int d) {
      edge_grids_[d].visit(edge_boxes_[e], [&](int o) {
        const auto& b = edges_[o];
        if (o <= e && moved(b.data(), 2)) return;
        if (shares_vertex(a.data(), 2, b.data(), 2)) return;
        test({a[0], a[1], b[0], b[1]}, true, gap, hits);
      });
    });
    if (!body) continue;
    body_edge_grid_.visit(edge_boxes_[e], [&](int i) {
      const auto& c = edges_[cloth_edges_ + i];
      test({a[0], a[1], c[0], c[1]}, true, gap, hits);
    });
  }
}

void CollisionPass::file_body(double gap, const Box& region, const SweptBody& body) {
  // The body's features that sweep through `region` during the frame (or,
  // without a frame sweep, the substep), in their own grids.
  const double grow = 0.5 * gap;
  const bool frame = body.frame_start != nullptr && body.frame_end != nullptr;
  Vec3s& from = frame_from_;
  Vec3s& to = frame_to_;
  from.assign(x0_.size(), Vec3::Zero());
  to.assign(x0_.size(), Vec3::Zero());
  for (int i = 0; i < body_vertices_; ++i) {
    from[cloth_vertices_ + i] = frame ? (*body.frame_start)[i] : x0_[cloth_vertices_ + i];
    to[cloth_vertices_ + i] = frame ? (*body.frame_end)[i] : x1_[cloth_vertices_ + i];
  }
  const Box none{Vec3::Constant(std::nan("")), Vec3::Constant(std::nan(""))};
  const int nv = static_cast<int>(x0_.size()) - cloth_vertices_;
  const int ne = static_cast<int>(edges_.size()) - cloth_edges_;
  const int nf = static_cast<int>(faces_.size()) - cloth_faces_;
  body_vertex_boxes_.assign(static_cast<std::size_t>(nv), none);
  body_edge_boxes_.assign(static_cast<std::size_t>(ne), none);
  body_face_boxes_.assign(static_cast<std::size_t>(nf), none);
  for (int i = 0; i < nv; ++i) {
    const int v = cloth_vertices_ + i;
    const Box b = swept_box(from, to, &v, 1, grow);
    if (b.overlaps(region)) body_vertex_boxes_[i] = b;
  }
  for (int i = 0; i < ne; ++i) {
    const Box b = swept_box(from, to, edges_[cloth_edges_ + i].data(), 2, grow);
    if (b.overlaps(region)) body_edge_boxes_[i] = b;
  }
  for (int i = 0; i < nf; ++i) {
    const Box b = swept_box(from, to, faces_[cloth_faces_ + i].data(), 3, grow);
    if (b.overlaps(region)) body_face_boxes_[i] = b;
  }
  body_vertex_grid_.build(body_vertex_boxes_, body_cell_);
  body_edge_grid_.build(body_edge_boxes_, body_cell_);
  body_face_grid_.build(body_face_boxes_, body_cell_);
  body_region_ = region;
  body_frame_ = body.frame;
}

Vec3 CollisionPass::body_normal(const Hit& h) const {
  Vec3 n = Vec3::Zero();
  for (int v : h.v)
    if (owner_[v] < 0) n += body_normals_[v - cloth_vertices_];
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : n;
}

void CollisionPass::mark_pinched(const std::vector<Hit>& hits) {
  for (const Hit& h : hits) {
    // Only a cloth vertex against a body face: an edge or a face of the
    // cloth spans too much to say the body presses it from both sides.
    if (h.edge_edge || owner_[h.v[0]] < 0 || owner_[h.v[1]] >= 0) continue;
    const Vec3 n = body_normal(h);
    if (n.squaredNorm() == 0) continue;
    int from = -1;
    for (int v : h.v)
      if (owner_[v] < 0) from = v - cloth_vertices_;
    for (int v : h.v) {
      if (owner_[v] < 0) continue;
      if (pinch_dir_[v].squaredNorm() == 0) {
        pinch_dir_[v] = n;
        pinch_from_[v] = from;
      } else if (pinch_dir_[v].dot(n) < kPinchCos) {
        const Vec3s* apart = body_.apart;
        if (apart == nullptr || ((*apart)[pinch_from_[v]] - (*apart)[from]).norm() > kPinchApart) pinched_[v] = 1;
      }
    }
  }
}

bool CollisionPass::correct(const Hit& hit, double gap) {
  // A body pair with a cloth vertex the body presses from two opposite
  // sides: the body yields there (pushing it out of one side pushes it
  // into the other, and stretches the cloth round it).
  if (owner_[hit.v[0]] < 0 || owner_[hit.v[3]] < 0) {
    for (int v : hit.v)
      if (owner_[v] >= 0 && pinched_[v]) return true;
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
  layout(cloths, body);
  body_ = body;
  const std::size_t total = owner_.size();
  x0_.resize(total);
  x1_.resize(total);
  inv_mass_.resize(total);
  back_.assign(total, 0);
  dirty_.assign(total, 0);
  pinched_.assign(total, 0);
  pinch_dir_.assign(total, Vec3::Zero());
  pinch_from_.assign(total, -1);
  for (std::size_t c = 0; c < states.size(); ++c) {
    const Cloth::State& s = *states[c];
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      x0_[offset_[c] + i] = s.x_start[i];
      x1_[offset_[c] + i] = s.x[i];
      inv_mass_[offset_[c] + i] = s.inv_mass[i];
    }
  }
  for (int i = 0; i < body_vertices_; ++i) {
    x0_[cloth_vertices_ + i] = (*body.start)[i];
    x1_[cloth_vertices_ + i] = (*body.end)[i];
    inv_mass_[cloth_vertices_ + i] = 0.0;
  }
  // The body's vertex normals at the start (for starts_inside()).
  body_normals_.assign(static_cast<std::size_t>(std::max(body_vertices_, 0)), Vec3::Zero());
  for (int f = cloth_faces_; f < static_cast<int>(faces_.size()); ++f) {
    const auto& t = faces_[f];
    const Vec3 n = (x0_[t[1]] - x0_[t[0]]).cross(x0_[t[2]] - x0_[t[0]]);
    for (int k = 0; k < 3; ++k) body_normals_[t[k] - cloth_vertices_] += n;
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
      const int g = offset_[c] + static_cast<int>(i);
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
  for (int v = 0; v < cloth_vertices_; ++v)
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
  mark_pinched(hits);
  while (!hits.empty() && stats.rounds < rounds) {
    for (const Hit& h : hits) correct(h, gap);
    ++stats.rounds;
    again();
    mark_pinched(hits);
  }
  // Impact zones: the cloth vertices of cloth-cloth pairs still failing,
  // merged (union-find) with every zone they touch, each moved rigidly
  // with its mass's mean motion and spin (Harmon et al. 2008), which keeps
  // a zone's own pairs as far apart as they started; zones grow while new
  // pairs fail, for at most kZoneRounds rounds.
  const auto with_body = [&](const Hit& h) { return owner_[h.v[0]] < 0 || owner_[h.v[3]] < 0; };
  std::vector<int> parent;
  for (int round = 0; round < kZoneRounds; ++round) {
    bool any = false;
    for (const Hit& h : hits) any = any || !with_body(h);
    if (!any) break;
    if (parent.empty()) {
      parent.resize(static_cast<std::size_t>(cloth_vertices_));
      for (int v = 0; v < cloth_vertices_; ++v) parent[v] = -1;  // -1: in no zone
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
      const int g = offset_[c] + static_cast<int>(i);
      pushes[c][i] += x1_[g] - s.x[i];
      s.x[i] = x1_[g];
      reverted[c][i] = back_[g];
    }
  }
  return stats;
}

}  // namespace layers::sim::detail
