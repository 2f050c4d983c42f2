// layers/garment/garment_body.h -- what the garment templates measure: the
// shaped body posed in its T-pose (skin, joints, a body part per vertex),
// landmark heights and widths read from it, and the envelope a garment is
// fitted around (the skin, plus the vertices of garments already built
// when an outer layer goes over an inner one), with slab queries.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/body/body_model.h"
#include "layers/body/rotation.h"
#include "layers/geometry/mesh.h"

namespace layers::garment {

enum class Part : std::uint8_t {
  Torso,
  Neck,
  Head,
  LeftArm,
  RightArm,
  LeftHand,
  RightHand,
  LeftLeg,
  RightLeg,
  LeftFoot,
  RightFoot
};
using PartMask = std::uint32_t;
constexpr PartMask bit(Part p) { return PartMask{1} << static_cast<int>(p); }
constexpr PartMask kAllParts = 0x7ff;
constexpr PartMask kArms = bit(Part::LeftArm) | bit(Part::RightArm);
constexpr PartMask kHands = bit(Part::LeftHand) | bit(Part::RightHand);
constexpr PartMask kFeet = bit(Part::LeftFoot) | bit(Part::RightFoot);
constexpr PartMask kHeadNeck = bit(Part::Head) | bit(Part::Neck);

// The body the garments are made for, in its T-pose (arms along x, y up,
// facing +z, soles on y = 0).
struct TPoseBody {
  geometry::TriMesh mesh;          // skin vertices posed in the T-pose
  std::vector<body::Vec3> joints;  // T-pose joint positions
  std::vector<std::string> joint_names;
  std::vector<Part> parts;  // per skin vertex, from its dominant skinning joint

  body::Vec3 joint(const std::string& name) const;  // throws layers::Error when absent
};

// Poses `body` in its T-pose and labels the vertices.
TPoseBody t_pose_body(const body::Body& body);

// Heights (y) and widths (x) of the T-pose body that place the garments.
struct Landmarks {
  double crotch = 0;  // lowest midline point between the legs
  double knee = 0, ankle = 0, hip_joint = 0;
  double hip = 0;                                               // widest section between the crotch and the waist
  double waist = 0;                                             // narrowest torso section above the hips
  double armpit = 0;                                            // lowest point of the arms next to the torso
  double neck = 0;                                              // base of the neck (Neck joint)
  double neck_half_width = 0, neck_half_depth = 0, neck_z = 0;  // neck section at its base
  double shoulder_x = 0;                                        // |x| of the shoulder (LeftArm) joint
  double wrist_x = 0;                                           // |x| of the wrist (LeftHand) joint
  body::Vec3 head_centre = body::Vec3::Zero();
  double head_top = 0;
};
Landmarks measure(const TPoseBody& body);

// Points (each with a body part) that a garment has to enclose.
class Envelope {
 public:
  Envelope() = default;
  // The skin of `body`. Every mesh added is sampled at its vertices and
  // along its edges at most `kSpacing` apart (the skin's quads are up to
  // ~6 cm tall on the shins: vertices alone leave thin slabs empty).
  explicit Envelope(const TPoseBody& body);
  // Adds a garment; each point takes the part of its nearest skin vertex.
  void add_garment(const geometry::TriMesh& garment, const TPoseBody& body);
  static constexpr double kSpacing = 0.01;
  // The same points mirrored in x (left and right parts swapped), so that a
  // template written for the left side builds the right one.
  Envelope mirrored() const;

  int size() const { return static_cast<int>(points_.size()); }
  const body::Vec3& point(int i) const { return points_[i]; }
  Part part(int i) const { return parts_[i]; }

  // Indices of points with y (axis 1) or x (axis 0) in [lo, hi] whose part
  // is in `mask`.
  std::vector<int> slab(int axis, double lo, double hi, PartMask mask) const;

 private:
  void sort();
  // Appends the vertices and edge samples of a mesh with the given parts.
  void add_mesh(const geometry::TriMesh& mesh, const std::vector<Part>& vertex_parts);
  std::vector<body::Vec3> points_;
  std::vector<Part> parts_;
  std::vector<int> order_[2];  // indices sorted by x and by y
};

}  // namespace layers::garment
