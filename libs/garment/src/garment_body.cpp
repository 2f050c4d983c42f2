// garment_body.cpp -- the T-pose body the garment templates are fitted to:
// posing and part labels, landmark measurements, and the envelope (skin
// plus under-garments) with slab queries.
#include "layers/garment/garment_body.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "layers/body/pose_body.h"
#include "layers/core/error.h"
#include "layers/geometry/nearest.h"

namespace layers::garment {
namespace {

Part part_of_joint(const std::string& name) {
  static const std::map<std::string, Part> parts = {{"Head", Part::Head},
                                                    {"Neck", Part::Neck},
                                                    {"Neck1", Part::Neck},
                                                    {"LeftArm", Part::LeftArm},
                                                    {"LeftForeArm", Part::LeftArm},
                                                    {"RightArm", Part::RightArm},
                                                    {"RightForeArm", Part::RightArm},
                                                    {"LeftHand", Part::LeftHand},
                                                    {"LThumb", Part::LeftHand},
                                                    {"LeftFingerBase", Part::LeftHand},
                                                    {"LeftHandFinger1", Part::LeftHand},
                                                    {"RightHand", Part::RightHand},
                                                    {"RThumb", Part::RightHand},
                                                    {"RightFingerBase", Part::RightHand},
                                                    {"RightHandFinger1", Part::RightHand},
                                                    {"LeftUpLeg", Part::LeftLeg},
                                                    {"LeftLeg", Part::LeftLeg},
                                                    {"RightUpLeg", Part::RightLeg},
                                                    {"RightLeg", Part::RightLeg},
                                                    {"LeftFoot", Part::LeftFoot},
                                                    {"LeftToeBase", Part::LeftFoot},
                                                    {"RightFoot", Part::RightFoot},
                                                    {"RightToeBase", Part::RightFoot}};
  auto it = parts.find(name);
  return it == parts.end() ? Part::Torso : it->second;
}

Part mirror_part(Part p) {
  switch (p) {
    case Part::LeftArm:
      return Part::RightArm;
    case Part::RightArm:
      return Part::LeftArm;
    case Part::LeftHand:
      return Part::RightHand;
    case Part::RightHand:
      return Part::LeftHand;
    case Part::LeftLeg:
      return Part::RightLeg;
    case Part::RightLeg:
      return Part::LeftLeg;
    case Part::LeftFoot:
      return Part::RightFoot;
    case Part::RightFoot:
      return Part::LeftFoot;
    default:
      return p;
  }
}

body::Vec3 row(const geometry::Points& p, int i) { return p.row(i).transpose().cast<double>(); }

}  // namespace

body::Vec3 TPoseBody::joint(const std::string& name) const {
  for (std::size_t j = 0; j < joint_names.size(); ++j)
    if (joint_names[j] == name) return joints[j];
  throw Error("T-pose body has no joint '" + name + "'");
}

TPoseBody t_pose_body(const body::Body& body) {
  TPoseBody out;
  body::BodyFrame frame = body::pose_body(body, body.t_pose);
  out.mesh.vertices = std::move(frame.vertices);
  out.mesh.faces = body.rest.faces;
  out.joints = frame.joints.position;
  out.joint_names = body.skeleton.names;
  out.parts.resize(out.mesh.num_vertices());
  for (int v = 0; v < out.mesh.num_vertices(); ++v)
    out.parts[v] = part_of_joint(body.skeleton.names[body.weights.index(v, 0)]);
  return out;
}

Landmarks measure(const TPoseBody& body) {
  Landmarks m;
  const auto& V = body.mesh.vertices;
  const int n = body.mesh.num_vertices();
  auto avg_y = [&](const char* l, const char* r) { return 0.5 * (body.joint(l).y() + body.joint(r).y()); };
  m.knee = avg_y("LeftLeg", "RightLeg");
  m.ankle = avg_y("LeftFoot", "RightFoot");
  m.hip_joint = avg_y("LeftUpLeg", "RightUpLeg");
  m.neck = body.joint("Neck").y();
  m.shoulder_x = 0.5 * (body.joint("LeftArm").x() - body.joint("RightArm").x());
  m.wrist_x = 0.5 * (body.joint("LeftHand").x() - body.joint("RightHand").x());

  m.crotch = std::numeric_limits<double>::infinity();
  double neck_w = 0, neck_zlo = std::numeric_limits<double>::infinity(), neck_zhi = -neck_zlo;
  body::Vec3 head_lo = body::Vec3::Constant(std::numeric_limits<double>::infinity()), head_hi = -head_lo;
  int head_count = 0;
  for (int v = 0; v < n; ++v) {
    const body::Vec3 p = row(V, v);
    if (std::abs(p.x()) < 0.004 && p.y() > m.knee + 0.1 && p.y() < m.hip_joint + 0.1)
      m.crotch = std::min(m.crotch, p.y());
    if (body.parts[v] == Part::Neck && std::abs(p.y() - m.neck) < 0.02) {
      neck_w = std::max(neck_w, std::abs(p.x()));
      neck_zlo = std::min(neck_zlo, p.z());
      neck_zhi = std::max(neck_zhi, p.z());
    }
    if (body.parts[v] == Part::Head) {
      head_lo = head_lo.cwiseMin(p);
      head_hi = head_hi.cwiseMax(p);
      ++head_count;
    }
  }
  if (!std::isfinite(m.crotch) || head_count == 0 || !(neck_w > 0))
    throw Error("T-pose body: cannot find the crotch or the head");
  m.neck_half_width = neck_w;
  m.neck_half_depth = 0.5 * (neck_zhi - neck_zlo);
  m.neck_z = 0.5 * (neck_zhi + neck_zlo);
  m.head_centre = 0.5 * (head_lo + head_hi);
  m.head_top = head_hi.y();

  // Half-width of the torso (no arms, hands or head) in 1 cm slabs.
  auto half_width = [&](double y) {
    double w = 0;
    for (int v = 0; v < n; ++v) {
      const Part p = body.parts[v];
      if (p == Part::Torso || p == Part::LeftLeg || p == Part::RightLeg)
        if (std::abs(V(v, 1) - y) < 0.005) w = std::max(w, std::abs(static_cast<double>(V(v, 0))));
    }
    return w;
  };
  const double spine1 = body.joint("Spine1").y();
  double best = std::numeric_limits<double>::infinity();
  for (double y = m.hip_joint + 0.08; y <= spine1; y += 0.01) {
    const double w = half_width(y);
    if (w > 0 && w < best) best = w, m.waist = y;
  }
  best = 0;
  for (double y = m.crotch; y <= m.waist; y += 0.01) {
    const double w = half_width(y);
    if (w > best) best = w, m.hip = y;
  }
  m.armpit = std::numeric_limits<double>::infinity();
  for (int v = 0; v < n; ++v) {
    const Part p = body.parts[v];
    if ((p == Part::LeftArm || p == Part::RightArm) && std::abs(V(v, 0)) < m.shoulder_x + 0.1)
      m.armpit = std::min(m.armpit, static_cast<double>(V(v, 1)));
  }
  return m;
}

Envelope::Envelope(const TPoseBody& body) {
  add_mesh(body.mesh, body.parts);
  sort();
}

void Envelope::add_garment(const geometry::TriMesh& garment, const TPoseBody& body) {
  geometry::PointIndex skin(body.mesh.vertices);
  const Eigen::VectorXi nearest = skin.nearest_all(garment.vertices);
  std::vector<Part> parts(garment.num_vertices(), Part::Torso);
  for (int v = 0; v < garment.num_vertices(); ++v)
    if (nearest[v] >= 0) parts[v] = body.parts[nearest[v]];
  add_mesh(garment, parts);
  sort();
}

void Envelope::add_mesh(const geometry::TriMesh& mesh, const std::vector<Part>& vertex_parts) {
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    points_.push_back(row(mesh.vertices, v));
    parts_.push_back(vertex_parts[v]);
  }
  // Each undirected edge once (from its lower-indexed end).
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      if (a > b) continue;
      const body::Vec3 pa = row(mesh.vertices, a), pb = row(mesh.vertices, b);
      const int n = static_cast<int>(std::ceil((pb - pa).norm() / kSpacing));
      for (int i = 1; i < n; ++i) {
        points_.push_back(pa + (pb - pa) * (static_cast<double>(i) / n));
        parts_.push_back(vertex_parts[2 * i < n ? a : b]);
      }
    }
}

Envelope Envelope::mirrored() const {
  Envelope out;
  out.points_ = points_;
  out.parts_ = parts_;
  for (auto& p : out.points_) p.x() = -p.x();
  for (auto& p : out.parts_) p = mirror_part(p);
  out.sort();
  return out;
}

void Envelope::sort() {
  for (int axis = 0; axis < 2; ++axis) {
    auto& o = order_[axis];
    o.resize(points_.size());
    for (std::size_t i = 0; i < o.size(); ++i) o[i] = static_cast<int>(i);
    std::stable_sort(o.begin(), o.end(), [&](int a, int b) { return points_[a][axis] < points_[b][axis]; });
  }
}

std::vector<int> Envelope::slab(int axis, double lo, double hi, PartMask mask) const {
  const auto& o = order_[axis];
  auto first = std::lower_bound(o.begin(), o.end(), lo, [&](int i, double v) { return points_[i][axis] < v; });
  std::vector<int> out;
  for (auto it = first; it != o.end() && points_[*it][axis] <= hi; ++it)
    if (mask & bit(parts_[*it])) out.push_back(*it);
  return out;
}

}  // namespace layers::garment
