// Part-based self-intersection test (see self_intersection.h).
#include "layers/body/self_intersection.h"

#include <algorithm>
#include <cctype>
#include <memory>

#include "layers/geometry/intersect.h"
#include "layers/geometry/nearest.h"
#include "layers/geometry/normals.h"
#include "layers/geometry/topology.h"

namespace layers::body {
namespace {

constexpr float kCoreWeight = 0.99f;
constexpr int kBlendRings = 2;            // rings of core vertices next to a blend zone that are not trusted as surface
constexpr double kGapFromShoulder = 0.4;  // arm gaps count beyond this share of the upper arm from the shoulder
constexpr double kGapFromHip = 0.3;       // the thigh gap counts beyond this share of the thigh from the hip

int part_of_joint(const std::string& name) {
  auto has = [&](const char* s) { return name.find(s) != std::string::npos; };
  const bool left = name.rfind("Left", 0) == 0 ||
                    (name.size() > 1 && name[0] == 'L' && std::isupper(static_cast<unsigned char>(name[1])));
  if (has("Shoulder")) return static_cast<int>(BodyPart::torso);  // clavicles move with the chest
  if (has("Arm") || has("Hand") || has("Thumb") || has("Finger"))
    return static_cast<int>(left ? BodyPart::left_arm : BodyPart::right_arm);
  if (has("UpLeg") || has("Leg") || has("Foot") || has("Toe"))
    return static_cast<int>(left ? BodyPart::left_leg : BodyPart::right_leg);
  return static_cast<int>(BodyPart::torso);
}

struct Box {
  Eigen::RowVector3f lo = Eigen::RowVector3f::Constant(1e30f), hi = Eigen::RowVector3f::Constant(-1e30f);
  void add(const Eigen::RowVector3f& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool contains(const Eigen::RowVector3f& p, float margin) const {
    return (p.array() >= lo.array() - margin).all() && (p.array() <= hi.array() + margin).all();
  }
  // Farther apart than `margin` along some axis.
  bool apart(const Box& o, float margin) const {
    return (lo.array() > o.hi.array() + margin).any() || (o.lo.array() > hi.array() + margin).any();
  }
};

// The part pairs tested (a against b's surface, or a's faces against b's):
// each arm against the rest, each leg against the torso and the other leg.
constexpr std::array<std::pair<int, int>, 10> kPairs = {
    {{1, 0}, {2, 0}, {1, 3}, {1, 4}, {2, 3}, {2, 4}, {1, 2}, {3, 4}, {3, 0}, {4, 0}}};

// The limbs a crossing between parts a and b is attributed to: the arms
// among them, else both legs.
std::array<bool, 4> moved_limbs(int a, int b) {
  std::array<bool, 4> m{};
  m[0] = a == 1 || b == 1;
  m[1] = a == 2 || b == 2;
  if (!m[0] && !m[1]) m[2] = m[3] = true;
  return m;
}

// Limb index (0..3) of a part, -1 for the torso.
int limb(int part) { return part - 1; }

}  // namespace

const char* body_part_name(BodyPart part) {
  switch (part) {
    case BodyPart::torso:
      return "torso";
    case BodyPart::left_arm:
      return "left_arm";
    case BodyPart::right_arm:
      return "right_arm";
    case BodyPart::left_leg:
      return "left_leg";
    case BodyPart::right_leg:
      return "right_leg";
  }
  return "?";
}

SelfIntersection::SelfIntersection(const Body& body, IntersectionOptions options) : body_(body), options_(options) {
  const int nv = body.num_vertices();
  std::vector<int> joint_part(body.skeleton.num_joints());
  for (int j = 0; j < body.skeleton.num_joints(); ++j) joint_part[j] = part_of_joint(body.skeleton.names[j]);
  part_.assign(nv, -1);
  std::vector<std::array<float, kNumBodyParts>> share(nv);
  for (int v = 0; v < nv; ++v) {
    share[v].fill(0.0f);
    for (int k = 0; k < 4; ++k) share[v][joint_part[body.weights.index(v, k)]] += body.weights.weight(v, k);
    for (int p = 0; p < kNumBodyParts; ++p)
      if (share[v][p] >= kCoreWeight) part_[v] = p;
  }
  const int nf = static_cast<int>(body.rest.faces.rows());
  region_.assign(nf, static_cast<signed char>(BodyPart::torso));
  for (int f = 0; f < nf; ++f) {
    for (int p = 1; p < kNumBodyParts; ++p) {
      float mean = 0.0f;
      for (int k = 0; k < 3; ++k) mean += share[body.rest.faces(f, k)][p] / 3.0f;
      if (mean >= 0.5f) region_[f] = static_cast<signed char>(p);
    }
    region_faces_[region_[f]].push_back(f);
  }
  // Core vertices within a few rings of a blend zone.
  const geometry::Adjacency adj = geometry::vertex_adjacency(body.rest.faces, nv);
  std::vector<char> mark(nv, 0);
  for (int v = 0; v < nv; ++v) mark[v] = part_[v] < 0;
  for (int ring = 0; ring < kBlendRings; ++ring) {
    std::vector<char> next = mark;
    for (int v = 0; v < nv; ++v)
      if (mark[v])
        for (const int* n = adj.begin(v); n != adj.end(v); ++n) next[*n] = 1;
    mark.swap(next);
  }
  near_blend_ = mark;
  // Limb vertices whose gap counts (arm to torso, left leg to right leg):
  // away from the shoulder and the hip, where the limb always lies against
  // its neighbour and no turn about the joint opens it.
  gap_vertex_.assign(nv, 0);
  const std::array<int, kNumBodyParts> limb_root{-1, body.skeleton.index("LeftArm"), body.skeleton.index("RightArm"),
                                                 body.skeleton.index("LeftUpLeg"), body.skeleton.index("RightUpLeg")};
  for (int v = 0; v < nv; ++v) {
    const int p = part_[v];
    if (p <= 0) continue;
    const int j = limb_root[p];
    if (j < 0) continue;
    const double from_root = (body.rest.vertices.row(v).cast<double>().transpose() - body.skeleton.rest_head[j]).norm();
    gap_vertex_[v] = from_root > (p <= 2 ? kGapFromShoulder : kGapFromHip) * body.skeleton.bone_length(j);
  }
  for (int v = 0; v < nv; ++v)
    if (part_[v] >= 0) members_[part_[v]].push_back(v);
}

FrameIntersection SelfIntersection::check(const geometry::Points& posed) const {
  return check(posed, {true, true, true, true});
}

FrameIntersection SelfIntersection::check(const geometry::Points& posed, const std::array<bool, 4>& crossings) const {
  FrameIntersection out;
  const geometry::Points normals = geometry::vertex_normals(posed, body_.rest.faces);
  std::array<Box, kNumBodyParts> box;
  for (int p = 0; p < kNumBodyParts; ++p)
    for (int v : members_[p]) box[p].add(posed.row(v));

  const float gate = static_cast<float>(options_.max_distance);
  std::array<std::unique_ptr<geometry::PointIndex>, kNumBodyParts> index;
  for (const auto& [a, b] : kPairs) {
    if (box[a].apart(box[b], gate)) continue;
    if (!index[b]) {
      geometry::Points pts(static_cast<Eigen::Index>(members_[b].size()), 3);
      for (std::size_t i = 0; i < members_[b].size(); ++i)
        pts.row(static_cast<Eigen::Index>(i)) = posed.row(members_[b][i]);
      index[b] = std::make_unique<geometry::PointIndex>(std::move(pts));
    }
    for (int v : members_[a]) {
      const Eigen::RowVector3f x = posed.row(v);
      if (!box[b].contains(x, gate)) continue;
      const geometry::Neighbour n = index[b]->nearest(x);
      if (n.index < 0 || n.distance > gate) continue;
      const int h = members_[b][n.index];
      if (near_blend_[h]) continue;
      const double offset = static_cast<double>((x - posed.row(h)).dot(normals.row(h)));
      if (b == 0 && (a == 1 || a == 2) && gap_vertex_[v])
        out.arm_gap[a - 1] = std::min(out.arm_gap[a - 1], std::max(offset, 0.0));
      if (a == 3 && b == 4 && gap_vertex_[v]) out.thigh_gap = std::min(out.thigh_gap, std::max(offset, 0.0));
      // The limb meets b at its root (limb/torso, thigh/thigh): the gap
      // counts only beyond the share of the bone from the joint.
      const bool beside = b == 0 || (a == 3 && b == 4);
      const double required = options_.gap > 0.0 && (!beside || gap_vertex_[v]) ? options_.gap : -options_.tolerance;
      const double shortfall = required - offset;
      const double depth = std::max(-offset, 0.0);
      if (shortfall > 0.0) ++out.vertices;
      out.depth = std::max(out.depth, depth);
      out.shortfall = std::max(out.shortfall, shortfall);
      // Arms move for any contact; legs share leg/leg and leg/torso contact.
      const bool arm = a == 1 || a == 2;
      for (int l : {arm ? limb(a) : 2, arm ? limb(a) : 3}) {
        out.limb_depth[l] = std::max(out.limb_depth[l], depth);
        out.limb_shortfall[l] = std::max(out.limb_shortfall[l], shortfall);
      }
    }
  }
  if (options_.exact) count_crossings(posed, crossings, out);
  return out;
}

void SelfIntersection::count_crossings(const geometry::Points& posed, const std::array<bool, 4>& wanted,
                                       FrameIntersection& out) const {
  // One face tree per region (only the regions a wanted pair needs, only
  // when the two regions' boxes overlap); a pair's count is crossings() of
  // one region's faces against the other's tree.
  std::array<Box, kNumBodyParts> box;
  for (int p = 0; p < kNumBodyParts; ++p)
    for (int f : region_faces_[p])
      for (int k = 0; k < 3; ++k) box[p].add(posed.row(body_.rest.faces(f, k)));
  const auto submesh = [&](int p) {
    geometry::TriMesh m{posed, geometry::Faces(static_cast<Eigen::Index>(region_faces_[p].size()), 3)};
    for (std::size_t i = 0; i < region_faces_[p].size(); ++i)
      m.faces.row(static_cast<Eigen::Index>(i)) = body_.rest.faces.row(region_faces_[p][i]);
    return m;
  };
  std::array<std::unique_ptr<geometry::FaceTree>, kNumBodyParts> tree;
  std::array<std::unique_ptr<geometry::TriMesh>, kNumBodyParts> mesh;
  for (const auto& [a, b] : kPairs) {
    const std::array<bool, 4> moved = moved_limbs(a, b);
    bool asked = false;
    for (int limb = 0; limb < 4; ++limb) asked = asked || (moved[limb] && wanted[limb]);
    if (!asked || region_faces_[a].empty() || region_faces_[b].empty() || box[a].apart(box[b], 0.0f)) continue;
    if (!mesh[a]) mesh[a] = std::make_unique<geometry::TriMesh>(submesh(a));
    if (!tree[b]) tree[b] = std::make_unique<geometry::FaceTree>(submesh(b));
    const int n = static_cast<int>(geometry::crossings(*mesh[a], *tree[b]).pairs);
    out.crossings += n;
    for (int limb = 0; limb < 4; ++limb) out.limb_crossings[limb] += moved[limb] ? n : 0;
  }
}

}  // namespace layers::body
