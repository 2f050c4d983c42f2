// The shared broad phase (contact_candidates.h, box_tree.h): every pair of
// features that the brute force finds within its reach is listed, while
// the cloths stay in their bounds and after some vertices leave them (a
// local refresh) or many do (the whole lists again: the fall-back), in the
// global and the per-contact lists; the body's pairs follow its sweep; the
// same inputs give the same lists.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "box_tree.h"
#include "contact_candidates.h"
#include "fixtures.h"
#include "layers/geometry/topology.h"

namespace layers::sim {
namespace {

using test::grid;
using test::V3;
using Pairs = std::set<std::array<int, 2>>;
using detail::Box;

Box box_of(const Vec3s& x0, const Vec3s& x1, const int* v, int n) {
  Box b{x0[v[0]], x0[v[0]]};
  for (int k = 0; k < n; ++k) {
    b.lo = b.lo.cwiseMin(x0[v[k]]).cwiseMin(x1[v[k]]);
    b.hi = b.hi.cwiseMax(x0[v[k]]).cwiseMax(x1[v[k]]);
  }
  return b;
}

bool shares(const int* a, int na, const int* b, int nb) {
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nb; ++j)
      if (a[i] == b[j]) return true;
  return false;
}

// What the lists must hold, by brute force over the swept boxes of the
// features between positions x0 and x1 (cloth vertices, then the body's).
struct Needed {
  Pairs vf, ee, body_vf, body_fv, body_ee;
};
Needed brute_force(const detail::ContactLayout& L, const Vec3s& x0, const Vec3s& x1,
                   const detail::ContactCandidates::Reach& r) {
  Needed n;
  const int cv = L.cloth_vertices;
  const auto partners = [&](int c, int d) { return c != d || L.self[c]; };
  for (int v = 0; v < cv; ++v) {
    const Box bv = box_of(x0, x1, &v, 1);
    for (int f = 0; f < static_cast<int>(L.faces.size()); ++f) {
      const auto& t = L.faces[f];
      const bool body = f >= L.cloth_faces;
      if (!body && (!partners(L.owner[v], L.owner[t[0]]) || shares(&v, 1, t.data(), 3))) continue;
      if (!detail::near(bv, box_of(x0, x1, t.data(), 3), r.gap)) continue;
      (body ? n.body_vf : n.vf).insert({v, body ? f - L.cloth_faces : f});
    }
  }
  for (int f = 0; f < L.cloth_faces; ++f) {
    const Box bf = box_of(x0, x1, L.faces[f].data(), 3);
    for (int i = 0; i < L.body_vertices; ++i) {
      const int v = cv + i;
      if (detail::near(bf, box_of(x0, x1, &v, 1), r.gap)) n.body_fv.insert({f, i});
    }
  }
  for (int e = 0; e < L.cloth_edges; ++e) {
    const auto& a = L.edges[e];
    const Box be = box_of(x0, x1, a.data(), 2);
    for (int o = e + 1; o < static_cast<int>(L.edges.size()); ++o) {
      const auto& b = L.edges[o];
      const bool body = o >= L.cloth_edges;
      const Box bo = box_of(x0, x1, b.data(), 2);
      if (body) {
        if (detail::near(be, bo, std::max(r.gap, r.body_edges))) n.body_ee.insert({e, o - L.cloth_edges});
        continue;
      }
      const int c = L.owner[a[0]], d = L.owner[b[0]];
      if (!partners(c, d) || shares(a.data(), 2, b.data(), 2)) continue;
      const double reach = L.layer[c] != L.layer[d] ? std::max(r.gap, r.layer_edges) : r.gap;
      if (detail::near(be, bo, reach)) n.ee.insert({e, o});
    }
  }
  return n;
}

std::vector<std::array<int, 2>> ids(const std::vector<detail::ContactCandidates::BodyPair>& pairs) {
  std::vector<std::array<int, 2>> out;
  for (const auto& p : pairs) out.push_back(p.ids);
  return out;
}

// Every needed pair is listed (the lists may hold more).
void expect_listed(const Pairs& needed, const std::vector<std::array<int, 2>>& listed, const char* what) {
  const Pairs have(listed.begin(), listed.end());
  EXPECT_EQ(have.size(), listed.size()) << what << ": a pair listed twice";
  long missing = 0;
  for (const auto& p : needed) missing += have.count(p) == 0 ? 1 : 0;
  EXPECT_EQ(missing, 0) << what << ": " << missing << " of " << needed.size() << " needed pairs not listed";
}

TEST(ContactCandidates, ListEveryPairWithinReachThroughRefreshesAndRemakes) {
  // Two stacked sheets 5 mm apart (layers 0 and 1), a third with
  // self-contact, and a "body" (a sheet below, moving over the frame).
  std::vector<Cloth> cloths;
  cloths.emplace_back(grid(V3(0, 0, 0), V3(0.2, 0, 0), V3(0, 0, 0.2), 8, 8), Material{}, ClothOptions("inner", 0));
  cloths.emplace_back(grid(V3(0, 0.005, 0), V3(0.2, 0, 0), V3(0, 0, 0.2), 8, 8), Material{}, ClothOptions("outer", 1));
  cloths.emplace_back(grid(V3(0, 0.012, 0), V3(0.2, 0, 0), V3(0, 0, 0.2), 7, 7), Material{},
                      ClothOptions("folded", 1, true));
  const geometry::TriMesh body_mesh = grid(V3(0, -0.004, 0), V3(0.2, 0, 0), V3(0, 0, 0.2), 12, 12);
  std::vector<std::array<int, 3>> body_faces;
  for (Eigen::Index f = 0; f < body_mesh.faces.rows(); ++f)
    body_faces.push_back({body_mesh.faces(f, 0), body_mesh.faces(f, 1), body_mesh.faces(f, 2)});
  const geometry::Edges body_edges = geometry::unique_edges(body_mesh.faces);
  Vec3s body_from, body_to;
  for (Eigen::Index i = 0; i < body_mesh.vertices.rows(); ++i) {
    body_from.push_back(body_mesh.vertices.row(i).cast<double>().transpose());
    body_to.push_back(body_from.back() + Vec3(0.01, 0.002, 0));
  }

  detail::ContactLayout L;
  ASSERT_TRUE(L.update(cloths, &body_faces, &body_edges, &body_from));
  EXPECT_FALSE(L.update(cloths, &body_faces, &body_edges, &body_from));  // unchanged: not laid out again
  const detail::ContactCandidates::Reach reach{5e-4, 6e-3, 2e-3, 2e-3};
  detail::ContactCandidates candidates;
  candidates.set_reach(reach);

  Vec3s x0;
  for (const Cloth& c : cloths)
    for (const Vec3& p : c.state().x) x0.push_back(p);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> small(-0.0015, 0.0015), large(-0.02, 0.02), away(0.1, 0.2);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(x0.size()) - 1);
  long sweep = 0;
  for (int step = 0; step < 16; ++step) {
    // Small moves mostly (within the margin of the last lists); every
    // fourth step a few vertices thrown 10-20 cm (a local refresh) or, every
    // eighth, all of them (the whole lists again).
    Vec3s x1 = x0;
    for (Vec3& p : x1) p += Vec3(small(rng), small(rng), small(rng));
    const long builds = candidates.builds(), refreshes = candidates.refreshes();
    if (step % 8 == 7) {
      for (Vec3& p : x1) p += Vec3(large(rng), large(rng), large(rng));
    } else if (step % 4 == 3) {
      for (int k = 0; k < 3; ++k) x1[pick(rng)] += Vec3(away(rng), -away(rng), away(rng));
    }
    if (step % 3 == 0) ++sweep;  // the body's frame changes every third step
    const detail::ContactCandidates::BodySweep body{&body_from, &body_to, sweep};
    const bool made = candidates.ensure(
        L, [&](int g) -> const Vec3& { return x0[g]; }, [&](int g) -> const Vec3& { return x1[g]; }, body);
    if (step % 8 == 7) {
      EXPECT_TRUE(made);
      EXPECT_EQ(candidates.builds(), builds + 1) << "step " << step;
    } else if (step % 4 == 3) {
      EXPECT_TRUE(made);
      EXPECT_EQ(candidates.builds(), builds) << "step " << step;
      EXPECT_GT(candidates.refreshes(), refreshes) << "step " << step;
    }
    // The brute force on the substep's sweep, the body anywhere on its frame's.
    Vec3s all0 = x0, all1 = x1;
    all0.insert(all0.end(), body_from.begin(), body_from.end());
    all1.insert(all1.end(), body_to.begin(), body_to.end());
    const Needed n = brute_force(L, all0, all1, reach);
    expect_listed(n.vf, candidates.cloth_vertex_face(), "cloth vertex-face");
    expect_listed(n.ee, candidates.cloth_edge_edge(), "cloth edge-edge");
    expect_listed(n.body_vf, ids(candidates.body_vertex_face()), "body vertex-face");
    expect_listed(n.body_fv, ids(candidates.body_face_vertex()), "body face-vertex");
    expect_listed(n.body_ee, candidates.body_edge_edge(), "body edge-edge");
    EXPECT_FALSE(n.vf.empty());
    EXPECT_FALSE(n.ee.empty());
    EXPECT_FALSE(n.body_ee.empty());
    // The per-contact lists hold the same pairs in local indices: cloth 0
    // (layer 0) is inner to cloths 1 and 2 (layer 1).
    for (int outer : {1, 2}) {
      Pairs local;
      for (const auto& [e, o] : n.ee) {
        if (L.owner[L.edges[e][0]] == 0 && L.owner[L.edges[o][0]] == outer)
          local.insert({o - L.edge_offset[outer], e - L.edge_offset[0]});
      }
      expect_listed(local, candidates.layer_edge_pairs(0, outer), "layer edge pairs");
    }
    Pairs body_local;
    for (const auto& [e, i] : n.body_ee)
      if (L.owner[L.edges[e][0]] == 1) body_local.insert({e - L.edge_offset[1], i});
    expect_listed(body_local, candidates.body_edge_pairs(1), "body edge pairs of cloth 1");
    x0 = x1;
  }
  // Small moves kept most lists: far fewer whole makes than steps.
  EXPECT_LT(candidates.builds(), 12);
  EXPECT_GE(candidates.refreshes(), 2);
  EXPECT_GE(candidates.body_builds(), 1);
}

TEST(ContactCandidates, TheSameInputsGiveTheSameLists) {
  std::vector<Cloth> cloths;
  cloths.emplace_back(grid(V3(0, 0, 0), V3(0.2, 0, 0), V3(0, 0, 0.2), 9, 9), Material{}, ClothOptions("a", 0));
  cloths.emplace_back(grid(V3(0, 0.004, 0), V3(0.2, 0, 0), V3(0, 0, 0.2), 9, 9), Material{}, ClothOptions("b", 1));
  detail::ContactLayout L;
  L.update(cloths, nullptr, nullptr, nullptr);
  Vec3s x;
  for (const Cloth& c : cloths)
    for (const Vec3& p : c.state().x) x.push_back(p);
  const auto lists = [&] {
    detail::ContactCandidates c;
    c.set_reach({5e-4, 6e-3, 0, 3e-3});
    c.ensure(
        L, [&](int g) -> const Vec3& { return x[g]; }, [&](int g) -> const Vec3& { return x[g]; }, {});
    return std::make_pair(c.cloth_vertex_face(), c.cloth_edge_edge());
  };
  const auto a = lists(), b = lists();
  EXPECT_EQ(a, b);
  EXPECT_FALSE(a.second.empty());
}

TEST(BoxTree, ReportsEveryPairWithinReachOnceAndNoOther) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> at(0, 1), size(0, 0.1);
  const auto boxes = [&](int n) {
    std::vector<Box> b;
    for (int i = 0; i < n; ++i) {
      const Vec3 lo(at(rng), at(rng), at(rng));
      b.push_back(Box{lo, lo + Vec3(size(rng), size(rng), size(rng))});
    }
    return b;
  };
  std::vector<Box> a = boxes(300), c = boxes(200);
  a[17].lo.x() = std::nan("");  // never reported
  detail::BoxTree ta, tc;
  ta.build(a);
  tc.build(c);
  // Moved boxes, refitted (not rebuilt): still exact.
  for (Box& b : c) {
    const Vec3 d(0.1 * at(rng), 0, -0.05 * at(rng));
    b.lo += d;
    b.hi += d;
  }
  tc.refit(c);
  Pairs found;
  long calls = 0;
  detail::BoxTree::pairs(ta, tc, 0.01, [&](int i, int j) {
    found.insert({i, j});
    ++calls;
  });
  Pairs expected;
  for (int i = 0; i < 300; ++i)
    for (int j = 0; j < 200; ++j)
      if (detail::near(a[i], c[j], 0.01)) expected.insert({i, j});
  EXPECT_EQ(found, expected);
  EXPECT_EQ(calls, static_cast<long>(found.size()));
  EXPECT_GT(expected.size(), 50u);
}

}  // namespace
}  // namespace layers::sim
