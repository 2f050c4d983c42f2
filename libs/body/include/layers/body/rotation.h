// layers/body/rotation.h -- rotation helpers shared by the skeleton, BVH
// import, retargeting and procedural motions. Doubles throughout; the
// per-frame outputs are converted to float at the very end.
//
// Euler angles follow the BVH / Blender convention: a rotation order "ZYX"
// means the matrix Rz * Ry * Rx (the first-named axis is outermost).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace layers::body {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

// Rotation by `angle` radians about `axis` (need not be unit length; a zero
// axis gives the identity).
Quat axis_angle(const Vec3& axis, double angle);
inline Quat rot_x(double a) { return axis_angle(Vec3::UnitX(), a); }
inline Quat rot_y(double a) { return axis_angle(Vec3::UnitY(), a); }
inline Quat rot_z(double a) { return axis_angle(Vec3::UnitZ(), a); }

// Euler angles (radians) composed in `order` (three of 'X','Y','Z'):
// angles[k] is the angle about order[k]; result = R(order[0]) R(order[1]) R(order[2]).
Quat euler(const char order[3], const double angles[3]);

// The smallest rotation taking direction `from` onto direction `to`.
Quat shortest_arc(const Vec3& from, const Vec3& to);

// The rotation taking the frame (a1, a2) onto (b1, b2): a1 onto b1 exactly,
// a2 as close to b2 as the first allows. Vectors need not be unit length
// but must not be parallel within a pair.
Quat aim(const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2);

// Spherical interpolation along the shorter arc.
Quat slerp(const Quat& a, const Quat& b, double t);

// Flips q to the hemisphere of `reference` (q and -q are the same rotation);
// keeps quaternion tracks continuous.
Quat same_hemisphere(const Quat& q, const Quat& reference);

// Rotation angle in [0, pi].
double angle_of(const Quat& q);

// Smooth 0..1 ramps of x in [0,1] (clamped outside): cubic (C1) and
// quintic (C2) smoothstep.
double smoothstep(double x);
double smootherstep(double x);

}  // namespace layers::body
