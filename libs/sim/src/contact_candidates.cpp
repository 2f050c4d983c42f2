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
  const int nb =
      body_pose != nullptr && body_faces != nullptr && body_edges != nullptr ? static_cast<int>(body_pose->size()) : 0;
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
    for (const auto& f : *body_faces)
      faces.push_back({cloth_vertices + f[0], cloth_vertices + f[1], cloth_vertices + f[2]});
  }
  return true;
}

void ContactCandidates::set_reach(const Reach& reach) {
  if (reach == reach_) return;
  reach_ = reach;
  layout_stamp_ = nullptr;  // made again at the next ensure()
}

void ContactCandidates::set_bound(int g) {
  // Ahead of the later position along the motion from the earlier one
  // (which the next substeps are likely to continue), with room for the
  // margin and back to the earlier position.
  const Vec3 d = to_[g] - from_[g];
  ref_[g] = to_[g] + kAhead * d;
  radius_[g] = reach_.margin + (1 + kAhead) * d.cwiseAbs().maxCoeff() + kSlack;
  if (!std::isfinite(radius_[g])) radius_[g] = std::nan("");  // never within: made again
  vertex_boxes_[g] = Box{ref_[g].array() - radius_[g], ref_[g].array() + radius_[g]};
}

Box ContactCandidates::feature_bound(const int* v, int n) const {
  Box b = vertex_boxes_[v[0]];
  for (int k = 1; k < n; ++k) {
    b.lo = b.lo.cwiseMin(vertex_boxes_[v[k]].lo);
    b.hi = b.hi.cwiseMax(vertex_boxes_[v[k]].hi);
  }
  return b;
}

void ContactCandidates::add_vertex_face(const ContactLayout& L, int v, int f) {
  const auto& t = L.faces[f];
  if (t[0] != v && t[1] != v && t[2] != v) vf_.push_back({v, f});
}

void ContactCandidates::add_edge_edge(const ContactLayout& L, int e, int o) {
  // e < o, both cloth edges.
  const auto& a = L.edges[e];
  const auto& b = L.edges[o];
  if (shares_vertex(a.data(), 2, b.data(), 2)) return;
  ee_.push_back({e, o});
  // Edges of two layers, also by (inner, outer) cloth in local indices.
  const int c = L.owner[a[0]], d = L.owner[b[0]];
  if (L.layer[c] < L.layer[d]) {
    layer_ee_[c * cloths_ + d].push_back({o - L.edge_offset[d], e - L.edge_offset[c]});
  } else if (L.layer[c] > L.layer[d]) {
    layer_ee_[d * cloths_ + c].push_back({e - L.edge_offset[c], o - L.edge_offset[d]});
  }
  if (reach_.gap > 0 && near(edge_boxes_[e], edge_boxes_[o], reach_.gap)) ee_gap_.push_back({e, o});
}

void ContactCandidates::add_body_edge(const ContactLayout& L, int e, int i) {
  body_ee_.push_back({e, i});
  const int c = L.owner[L.edges[e][0]];
  body_ee_by_cloth_[c].push_back({e - L.edge_offset[c], i});
  if (reach_.gap > 0 && near(edge_boxes_[e], body_edge_boxes_[i], reach_.gap)) {
    body_ee_gap_.push_back({{e, i}, body_edge_boxes_[i]});
  }
}

double ContactCandidates::edge_reach(const ContactLayout& L, int c, int d) const {
  return L.layer[c] != L.layer[d] ? std::max(reach_.gap, reach_.layer_edges) : reach_.gap;
}

void ContactCandidates::make(const ContactLayout& L, const BodySweep& body) {
  ++builds_;
  layout_stamp_ = &L;
  revision_ = L.revision;
  const int nv = L.cloth_vertices;
  ref_.resize(static_cast<std::size_t>(nv));
  radius_.resize(static_cast<std::size_t>(nv));
  vertex_boxes_.resize(static_cast<std::size_t>(nv));
  for (int g = 0; g < nv; ++g) set_bound(g);
  edge_boxes_.resize(static_cast<std::size_t>(L.cloth_edges));
  face_boxes_.resize(static_cast<std::size_t>(L.cloth_faces));
  for (int e = 0; e < L.cloth_edges; ++e) edge_boxes_[e] = feature_bound(L.edges[e].data(), 2);
  for (int f = 0; f < L.cloth_faces; ++f) face_boxes_[f] = feature_bound(L.faces[f].data(), 3);
  // One hierarchy per cloth and kind of feature, built when the layout
  // changed and refitted to the new bounds otherwise; the features around
  // each vertex (for local refreshes).
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
    const auto around = [&](const auto& features, int count, int per, std::vector<int>& start, std::vector<int>& list) {
      start.assign(static_cast<std::size_t>(nv) + 1, 0);
      for (int i = 0; i < count; ++i)
        for (int k = 0; k < per; ++k) ++start[features[i][k] + 1];
      for (int g = 0; g < nv; ++g) start[g + 1] += start[g];
      list.resize(static_cast<std::size_t>(start[nv]));
      std::vector<int> fill(start.begin(), start.end() - 1);
      for (int i = 0; i < count; ++i)
        for (int k = 0; k < per; ++k) list[fill[features[i][k]]++] = i;
    };
    around(L.edges, L.cloth_edges, 2, vertex_edge_start_, vertex_edges_);
    around(L.faces, L.cloth_faces, 3, vertex_face_start_, vertex_faces_);
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
  cloths_ = static_cast<std::size_t>(nc);
  layer_ee_.resize(static_cast<std::size_t>(nc * nc));
  for (auto& pairs : layer_ee_) pairs.clear();
  for (int c = 0; c < nc; ++c) {
    for (int d = 0; d < nc; ++d) {
      // A cloth without self-contact never meets its own features.
      if (d == c && !L.self[c]) continue;
      if (reach_.gap > 0) {
        BoxTree::pairs(vertex_trees_[c], face_trees_[d], reach_.gap, [&](int v, int f) { add_vertex_face(L, v, f); });
      }
      const double reach = edge_reach(L, c, d);
      if (d < c || !(reach > 0)) continue;
      BoxTree::pairs(edge_trees_[c], edge_trees_[d], reach, [&](int e, int o) {
        if (o > e) add_edge_edge(L, e, o);
      });
    }
  }
  make_body(L, body);
  --body_builds_;  // counted with the whole lists
}

void ContactCandidates::refresh(const ContactLayout& L) {
  ++refreshes_;
  const int nc = static_cast<int>(cloths_);
  // New bounds for the vertices that left theirs, and the features around
  // them (marked) with their bounds again.
  vertex_mark_.assign(static_cast<std::size_t>(L.cloth_vertices), 0);
  edge_mark_.assign(static_cast<std::size_t>(L.cloth_edges), 0);
  face_mark_.assign(static_cast<std::size_t>(L.cloth_faces), 0);
  marked_edges_.clear();
  marked_faces_.clear();
  for (int g : escaped_) {
    set_bound(g);
    vertex_mark_[g] = 1;
    for (int k = vertex_edge_start_[g]; k < vertex_edge_start_[g + 1]; ++k) {
      const int e = vertex_edges_[k];
      if (!edge_mark_[e]) marked_edges_.push_back(e);
      edge_mark_[e] = 1;
    }
    for (int k = vertex_face_start_[g]; k < vertex_face_start_[g + 1]; ++k) {
      const int f = vertex_faces_[k];
      if (!face_mark_[f]) marked_faces_.push_back(f);
      face_mark_[f] = 1;
    }
  }
  for (int e : marked_edges_) edge_boxes_[e] = feature_bound(L.edges[e].data(), 2);
  for (int f : marked_faces_) face_boxes_[f] = feature_bound(L.faces[f].data(), 3);
  for (int c = 0; c < nc; ++c) {
    vertex_trees_[c].refit(vertex_boxes_);
    edge_trees_[c].refit(edge_boxes_);
    face_trees_[c].refit(face_boxes_);
  }
  // Every pair with a marked feature goes ...
  const auto drop = [](auto& pairs, auto&& marked) {
    pairs.erase(std::remove_if(pairs.begin(), pairs.end(), marked), pairs.end());
  };
  drop(vf_, [&](const std::array<int, 2>& p) { return vertex_mark_[p[0]] || face_mark_[p[1]]; });
  drop(ee_, [&](const std::array<int, 2>& p) { return edge_mark_[p[0]] || edge_mark_[p[1]]; });
  drop(ee_gap_, [&](const std::array<int, 2>& p) { return edge_mark_[p[0]] || edge_mark_[p[1]]; });
  for (int inner = 0; inner < nc; ++inner) {
    for (int outer = 0; outer < nc; ++outer) {
      drop(layer_ee_[inner * cloths_ + outer], [&](const std::array<int, 2>& p) {
        return edge_mark_[p[0] + L.edge_offset[outer]] || edge_mark_[p[1] + L.edge_offset[inner]];
      });
    }
  }
  drop(body_vf_, [&](const BodyPair& p) { return vertex_mark_[p.ids[0]] != 0; });
  drop(body_fv_, [&](const BodyPair& p) { return face_mark_[p.ids[0]] != 0; });
  drop(body_ee_, [&](const std::array<int, 2>& p) { return edge_mark_[p[0]] != 0; });
  drop(body_ee_gap_, [&](const BodyPair& p) { return edge_mark_[p.ids[0]] != 0; });
  for (int c = 0; c < nc; ++c) {
    drop(body_ee_by_cloth_[c], [&](const std::array<int, 2>& p) { return edge_mark_[p[0] + L.edge_offset[c]] != 0; });
  }
  // ... and the marked features meet the hierarchies again (a pair of two
  // marked features once).
  const bool body = body_listed_;
  const double body_edge_reach = std::max(reach_.gap, reach_.body_edges);
  const auto partners = [&](int c, auto&& f) {
    for (int d = 0; d < nc; ++d)
      if (d != c || L.self[c]) f(d);
  };
  if (reach_.gap > 0) {
    for (int v : escaped_) {
      partners(L.owner[v], [&](int d) {
        face_trees_[d].query(vertex_boxes_[v], reach_.gap, [&](int f) { add_vertex_face(L, v, f); });
      });
      if (body) {
        body_face_tree_.query(vertex_boxes_[v], reach_.gap, [&](int i) {
          body_vf_.push_back({{v, i}, body_face_boxes_[i]});
        });
      }
    }
    for (int f : marked_faces_) {
      partners(L.owner[L.faces[f][0]], [&](int d) {
        vertex_trees_[d].query(face_boxes_[f], reach_.gap, [&](int v) {
          if (!vertex_mark_[v]) add_vertex_face(L, v, f);
        });
      });
      if (body) {
        body_vertex_tree_.query(face_boxes_[f], reach_.gap, [&](int i) {
          body_fv_.push_back({{f, i}, body_vertex_boxes_[i]});
        });
      }
    }
  }
  for (int e : marked_edges_) {
    const int c = L.owner[L.edges[e][0]];
    partners(c, [&](int d) {
      const double reach = edge_reach(L, c, d);
      if (!(reach > 0)) return;
      edge_trees_[d].query(edge_boxes_[e], reach, [&](int o) {
        if (o == e || (edge_mark_[o] && o < e)) return;
        add_edge_edge(L, std::min(e, o), std::max(e, o));
      });
    });
    if (body && body_edge_reach > 0) {
      body_edge_tree_.query(edge_boxes_[e], body_edge_reach, [&](int i) { add_body_edge(L, e, i); });
    }
  }
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
  const bool any = nb > 0 && body.from != nullptr && body.to != nullptr && static_cast<int>(body.from->size()) == nb &&
                   static_cast<int>(body.to->size()) == nb;
  // The same sweep as the last lists (only the cloths' bounds changed):
  // the body's boxes and hierarchies stand.
  const bool same = any && body_trees_built_ && body.revision >= 0 && body.revision == body_.revision &&
                    body.from == body_.from && body.to == body_.to && body_layout_ == L.revision;
  body_ = body;
  body_layout_ = L.revision;
  if (!same) fit_body(L, body, any);
  body_listed_ = any;
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
      BoxTree::pairs(vertex_trees_[c], body_face_tree_, reach_.gap, [&](int v, int i) {
        body_vf_.push_back({{v, i}, body_face_boxes_[i]});
      });
      BoxTree::pairs(face_trees_[c], body_vertex_tree_, reach_.gap, [&](int f, int i) {
        body_fv_.push_back({{f, i}, body_vertex_boxes_[i]});
      });
    }
    if (edge_reach > 0) {
      BoxTree::pairs(edge_trees_[c], body_edge_tree_, edge_reach, [&](int e, int i) { add_body_edge(L, e, i); });
    }
  }
}

}  // namespace layers::sim::detail
