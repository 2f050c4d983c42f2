// The body's pinch zones over a frame (see body_pinch.h).
#include "body_pinch.h"

#include "layers/geometry/intersect.h"
#include "layers/geometry/pinch.h"

namespace layers::sim::detail {

namespace {

// Per body vertex: every face around it in a pinch zone of `pose`.
std::vector<std::uint8_t> zones_at(const Vec3s& pose, const geometry::Faces& faces,
                                   const std::vector<geometry::TriMesh>& cloth, double distance) {
  geometry::TriMesh body;
  body.faces = faces;
  body.vertices.resize(static_cast<Eigen::Index>(pose.size()), 3);
  for (std::size_t i = 0; i < pose.size(); ++i) body.vertices.row(static_cast<Eigen::Index>(i)) = pose[i].cast<float>();
  const geometry::MeshCrossings self = geometry::self_crossings(geometry::FaceTree(body));
  const geometry::PinchZones zones =
      geometry::pinch_zones_under(body, self.pairs > 0 ? self.a_faces : std::vector<char>{}, distance, cloth);
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

const std::vector<std::uint8_t>& BodyPinch::update(const BodyCollider& body, const geometry::Faces& body_faces,
                                                   const std::vector<Cloth>& cloths, double distance) {
  std::vector<geometry::TriMesh> cloth;
  for (const Cloth& c : cloths) cloth.push_back(c.mesh());
  if (!carried_)
    start_ = zones_at(body.frame_start(), body_faces, cloth, distance);
  else
    start_.swap(end_);
  end_ = body.frame_end() == body.frame_start() ? start_ : zones_at(body.frame_end(), body_faces, cloth, distance);
  carried_ = true;
  frame_.resize(start_.size());
  for (std::size_t i = 0; i < frame_.size(); ++i) frame_[i] = start_[i] && end_[i];
  return frame_;
}

}  // namespace layers::sim::detail
