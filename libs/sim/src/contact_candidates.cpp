// The shared broad phase (see contact_candidates.h): the global layout of
// cloths and body, and the candidate pairs made from the cloth vertices'
// bounds and the body's frame sweep.
#include "contact_candidates.h"

#include <algorithm>
#include <cmath>

namespace layers::sim::detail {

namespace {

bool shares_vertex(const int* a, int na, const int* b, int nb) {
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nb; ++j)
      if (a[i] == b[j]) return true;
  return false;
}

}  // namespace

bool ContactLayout::update(const std::vector<Cloth>& cloths, const std::vector<std::array<int, 3>>* body_faces,
                           const geometry::Edges* body_edges, const Vec3s* body_pose) {
  std::vector<long> revisions;
  for (const Cloth& c : cloths) revisions.push_back(c.revision());
  const int nb = body_pose != nullptr && body_faces != nullptr && body_edges != nullptr
                     ? static_cast<int>(body_pose->size())
                     : 0;
  if (revision > 0 && revisions == revisions_ && body_faces == body_faces_ && body_edges == body_edges_ &&
      nb == body_count_) {
    return false;
  }
  revisions_ = revisions;
  body_faces_ = body_faces;
  body_edges_ = body_edges;
  body_count_ = nb;
  ++revision;
  offset.clear();
  edge_offset.clear();
  face_offset.clear();
  owner.clear();
  self.clear();
  layer.clear();
  edges.clear();
  faces.clear();
  for (std::size_t c = 0; c < cloths.size(); ++c) {
    const Cloth& cloth = cloths[c];
    const int off = static_cast<int>(owner.size());
    offset.push_back(off);
    edge_offset.push_back(static_cast<int>(edges.size()));
    face_offset.push_back(static_cast<int>(faces.size()));
    owner.insert(owner.end(), static_cast<std::size_t>(cloth.num_vertices()), static_cast<int>(c));
    self.push_back(cloth.self_contact() ? 1 : 0);
    layer.push_back(cloth.layer());
    const geometry::Edges& e = cloth.edges();
    for (Eigen::Index k = 0; k < e.rows(); ++k) edges.push_back({off + e(k, 0), off + e(k, 1)});
    for (const auto& f : cloth.topology().faces) faces.push_back({off + f[0], off + f[1], off + f[2]});
  }
  cloth_vertices = static_cast<int>(owner.size());
  cloth_edges = static_cast<int>(edges.size());
  cloth_faces = static_cast<int>(faces.size());
  body_vertices = nb;
  offset.push_back(cloth_vertices);
  edge_offset.push_back(cloth_edges);
  face_offset.push_back(cloth_faces);
  owner.insert(owner.end(), static_cast<std::size_t>(nb), -1);
  if (nb > 0) {
    for (Eigen::Index k = 0; k < body_edges->rows(); ++k)
      edges.push_back({cloth_vertices + (*body_edges)(k, 0), cloth_vertices + (*body_edges)(k, 1)});
    for (const auto& f : *body_faces) faces.push_back({cloth_vertices + f[0], cloth_vertices + f[1], cloth_vertices + f[2]});
  }
  return true;
}

void ContactCandidates::set_reach(const Reach& reach) {
  if (reach == reach_) return;
  reach_ = reach;
  layout_stamp_ = nullptr;  // made again at the next ensure()
}

void ContactCandidates::make(const ContactLayout& L, const BodySweep& body) {
  ++builds_;
  layout_stamp_ = &L;
  revision_ = L.revision;
  const int nv = L.cloth_vertices;
  ref_.resize(static_cast<std::size_t>(nv));
  radius_.resize(static_cast<std::size_t>(nv));
  vertex_boxes_.resize(static_cast<std::size_t>(nv));
  for (int g = 0; g < nv; ++g) {
    // Ahead of the later position along the motion from the earlier one
    // (which the next substeps are likely to continue), with room for the
    // margin and back to the earlier position.
    const Vec3 d = to_[g] - from_[g];
    ref_[g] = to_[g] + kAhead * d;
    radius_[g] = reach_.margin + (1 + kAhead) * d.cwiseAbs().maxCoeff() + kSlack;
    if (!std::isfinite(radius_[g])) radius_[g] = std::nan("");  // never within: made again
    vertex_boxes_[g] = Box{ref_[g].array() - radius_[g], ref_[g].array() + radius_[g]};
  }
  const auto feature_box = [&](const int* v, int n) {
    Box b = vertex_boxes_[v[0]];
    for (int k = 1; k < n; ++k) {
      b.lo = b.lo.cwiseMin(vertex_boxes_[v[k]].lo);
      b.hi = b.hi.cwiseMax(vertex_boxes_[v[k]].hi);
    }
    return b;
  };
  edge_boxes_.resize(static_cast<std::size_t>(L.cloth_edges));
  face_boxes_.resize(static_cast<std::size_t>(L.cloth_faces));
  for (int e = 0; e < L.cloth_edges; ++e) edge_boxes_[e] = feature_box(L.edges[e].data(), 2);
  for (int f = 0; f < L.cloth_faces; ++f) face_boxes_[f] = feature_box(L.faces[f].data(), 3);
  // One hierarchy per cloth and kind of feature, built when the layout
  // changed and refitted to the new bounds otherwise.
  const int nc = static_cast<int>(L.self.size());
  if (tree_revision_ != L.revision) {
    tree_revision_ = L.revision;
    vertex_trees_.assign(static_cast<std::size_t>(nc), BoxTree{});
    edge_trees_.assign(static_cast<std::size_t>(nc), BoxTree{});
    face_trees_.assign(static_cast<std::size_t>(nc), BoxTree{});
    for (int c = 0; c < nc; ++c) {
      vertex_trees_[c].build(vertex_boxes_, L.offset[c], L.offset[c + 1] - L.offset[c]);
      edge_trees_[c].build(edge_boxes_, L.edge_offset[c], L.edge_offset[c + 1] - L.edge_offset[c]);
      face_trees_[c].build(face_boxes_, L.face_offset[c], L.face_offset[c + 1] - L.face_offset[c]);
    }
    body_trees_built_ = false;
  } else {
    for (int c = 0; c < nc; ++c) {
      vertex_trees_[c].refit(vertex_boxes_);
      edge_trees_[c].refit(edge_boxes_);
      face_trees_[c].refit(face_boxes_);
    }
  }
  vf_.clear();
  ee_.clear();
  ee_gap_.clear();
  cloths_ = nc;
  layer_ee_.resize(static_cast<std::size_t>(nc * nc));
  for (auto& pairs : layer_ee_) pairs.clear();
  const double layer_reach = std::max(reach_.gap, reach_.layer_edges);
  for (int c = 0; c < nc; ++c) {
    for (int d = 0; d < nc; ++d) {
      // A cloth without self-contact never meets its own features.
      if (d == c && !L.self[c]) continue;
      if (reach_.gap > 0) {
        BoxTree::pairs(vertex_trees_[c], face_trees_[d], reach_.gap, [&](int v, int f) {
          const auto& t = L.faces[f];
          if (t[0] != v && t[1] != v && t[2] != v) vf_.push_back({v, f});
        });
      }
      const double reach = L.layer[c] != L.layer[d] ? layer_reach : reach_.gap;
      if (d < c || !(reach > 0)) continue;
      BoxTree::pairs(edge_trees_[c], edge_trees_[d], reach, [&](int e, int o) {
        if (o <= e) return;
        const auto& a = L.edges[e];
        const auto& b = L.edges[o];
        if (shares_vertex(a.data(), 2, b.data(), 2)) return;
        ee_.push_back({e, o});
        // Edges of two layers, also by (inner, outer) cloth in local indices.
        if (L.layer[c] < L.layer[d]) {
          layer_ee_[c * nc + d].push_back({o - L.edge_offset[d], e - L.edge_offset[c]});
        } else if (L.layer[c] > L.layer[d]) {
          layer_ee_[d * nc + c].push_back({e - L.edge_offset[c], o - L.edge_offset[d]});
        }
        if (reach_.gap > 0 && near(edge_boxes_[e], edge_boxes_[o], reach_.gap)) ee_gap_.push_back({e, o});
      });
    }
  }
  make_body(L, body);
  --body_builds_;  // counted with the whole lists
}

void ContactCandidates::make_body(const ContactLayout& L, const BodySweep& body) {
  ++body_builds_;
  body_vf_.clear();
  body_fv_.clear();
  body_ee_.clear();
  body_ee_gap_.clear();
  body_ee_by_cloth_.resize(L.self.size());
  for (auto& pairs : body_ee_by_cloth_) pairs.clear();
  const int nb = L.body_vertices;
  const bool any = nb > 0 && body.from != nullptr && body.to != nullptr &&
                   static_cast<int>(body.from->size()) == nb && static_cast<int>(body.to->size()) == nb;
  // The same sweep as the last lists (only the cloths' bounds changed):
  // the body's boxes and hierarchies stand.
  const bool same = any && body_trees_built_ && body.revision >= 0 && body.revision == body_.revision &&
                    body.from == body_.from && body.to == body_.to && body_layout_ == L.revision;
  body_ = body;
  body_layout_ = L.revision;
  if (!same) fit_body(L, body, any);
  if (any) traverse_body(L);
}

void ContactCandidates::fit_body(const ContactLayout& L, const BodySweep& body, bool any) {
  const int nb = L.body_vertices;
  body_vertex_boxes_.resize(any ? static_cast<std::size_t>(nb) : 0);
  body_edge_boxes_.resize(any ? L.edges.size() - L.cloth_edges : 0);
  body_face_boxes_.resize(any ? L.faces.size() - L.cloth_faces : 0);
  if (!any) return;
  const Vec3s& from = *body.from;
  const Vec3s& to = *body.to;
  for (int i = 0; i < nb; ++i) {
    body_vertex_boxes_[i] = Box{from[i].cwiseMin(to[i]).array() - kSlack, from[i].cwiseMax(to[i]).array() + kSlack};
  }
  const auto feature_box = [&](const int* v, int n) {
    Box b = body_vertex_boxes_[v[0] - L.cloth_vertices];
    for (int k = 1; k < n; ++k) {
      const Box& o = body_vertex_boxes_[v[k] - L.cloth_vertices];
      b.lo = b.lo.cwiseMin(o.lo);
      b.hi = b.hi.cwiseMax(o.hi);
    }
    return b;
  };
  for (std::size_t i = 0; i < body_edge_boxes_.size(); ++i)
    body_edge_boxes_[i] = feature_box(L.edges[L.cloth_edges + i].data(), 2);
  for (std::size_t i = 0; i < body_face_boxes_.size(); ++i)
    body_face_boxes_[i] = feature_box(L.faces[L.cloth_faces + i].data(), 3);
  // The body's hierarchies, built once per layout, refitted to each sweep.
  if (!any) return;
  if (!body_trees_built_) {
    body_trees_built_ = true;
    body_vertex_tree_.build(body_vertex_boxes_);
    body_edge_tree_.build(body_edge_boxes_);
    body_face_tree_.build(body_face_boxes_);
  } else {
    body_vertex_tree_.refit(body_vertex_boxes_);
    body_edge_tree_.refit(body_edge_boxes_);
    body_face_tree_.refit(body_face_boxes_);
  }
}

void ContactCandidates::traverse_body(const ContactLayout& L) {
  const double edge_reach = std::max(reach_.gap, reach_.body_edges);
  const int nc = static_cast<int>(L.self.size());
  for (int c = 0; c < nc; ++c) {
    if (reach_.gap > 0) {
      BoxTree::pairs(vertex_trees_[c], body_face_tree_, reach_.gap,
                     [&](int v, int i) { body_vf_.push_back({{v, i}, body_face_boxes_[i]}); });
      BoxTree::pairs(face_trees_[c], body_vertex_tree_, reach_.gap,
                     [&](int f, int i) { body_fv_.push_back({{f, i}, body_vertex_boxes_[i]}); });
    }
    if (edge_reach > 0) {
      BoxTree::pairs(edge_trees_[c], body_edge_tree_, edge_reach, [&](int e, int i) {
        body_ee_.push_back({e, i});
        body_ee_by_cloth_[c].push_back({e - L.edge_offset[c], i});
        if (reach_.gap > 0 && near(edge_boxes_[e], body_edge_boxes_[i], reach_.gap)) body_ee_gap_.push_back({{e, i}, body_edge_boxes_[i]});
      });
    }
  }
}

}  // namespace layers::sim::detail
