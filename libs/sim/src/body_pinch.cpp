// The body's pinch zones over a frame (see body_pinch.h).
#include "body_pinch.h"

#include <algorithm>

#include "layers/geometry/intersect.h"
#include "layers/geometry/pinch.h"

namespace layers::sim::detail {

namespace {

// Per body vertex: every face around it in a pinch zone of `pose`.
std::vector<std::uint8_t> zones_at(const Vec3s& pose, const geometry::Faces& faces, const geometry::Points& cloth,
                                   double longest, double distance) {
  geometry::TriMesh body;
  body.faces = faces;
  body.vertices.resize(static_cast<Eigen::Index>(pose.size()), 3);
  for (std::size_t i = 0; i < pose.size(); ++i) body.vertices.row(static_cast<Eigen::Index>(i)) = pose[i].cast<float>();
  const geometry::MeshCrossings self = geometry::self_crossings(geometry::FaceTree(body));

  const geometry::PinchZones zones =
      geometry::pinch_zones_under(body, self.pairs > 0 ? self.a_faces : std::vector<char>{}, distance, cloth, longest);
  // A vertex all of whose faces are in a zone: any body pair made of such
  // vertices crosses the body only where the measures count a pinch.
  std::vector<std::uint8_t> out(pose.size(), 1);
  for (int f = 0; f < body.num_faces(); ++f) {
    if (zones.faces[f]) continue;
    for (int k = 0; k < 3; ++k) out[body.faces(f, k)] = 0;
  }
  return out;
}

}  // namespace

const std::vector<std::uint8_t>& BodyPinch::update(const BodyCollider& body, const std::vector<Cloth>& cloths,
                                                   double distance) {
  Eigen::Index rows = 0;
  for (const Cloth& c : cloths) rows += c.num_vertices();
  geometry::Points cloth(rows, 3);
  double longest = 0;
  Eigen::Index row = 0;
  for (const Cloth& c : cloths) {
    const Vec3s& x = c.state().x;
    for (const Vec3& p : x) cloth.row(row++) = p.cast<float>();
    const geometry::Edges& e = c.edges();
    for (Eigen::Index i = 0; i < e.rows(); ++i) longest = std::max(longest, (x[e(i, 0)] - x[e(i, 1)]).norm());
  }
  geometry::Faces faces(static_cast<Eigen::Index>(body.topology().faces.size()), 3);
  for (std::size_t f = 0; f < body.topology().faces.size(); ++f)
    for (int k = 0; k < 3; ++k) faces(static_cast<Eigen::Index>(f), k) = body.topology().faces[f][k];
  if (!carried_)
    start_ = zones_at(body.frame_start(), faces, cloth, longest, distance);
  else
    start_.swap(end_);
  end_ = body.frame_end() == body.frame_start() ? start_ : zones_at(body.frame_end(), faces, cloth, longest, distance);
  carried_ = true;
  frame_.resize(start_.size());
  for (std::size_t i = 0; i < frame_.size(); ++i) frame_[i] = start_[i] && end_[i];
  return frame_;
}

}  // namespace layers::sim::detail
