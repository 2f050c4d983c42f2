// layers/garment/garment_section.h -- cross-sections that garment panels are
// wrapped on: the convex hull of the envelope points in a slab, dilated by
// the ease, as a star-shaped curve (a radius per angle around a centre),
// and polyline helpers (arc-length resampling). Horizontal sections live
// in the (x, z) plane with angle 0 = +x (body's left), pi/2 = +z (front);
// sagittal sections in the (z, y) plane with angle 0 = +z, pi/2 = +y (up).
#pragma once

#include <vector>

#include "layers/garment/garment_body.h"
#include "layers/garment/garment_triangulate.h"

namespace layers::garment {

// Convex hull (counter-clockwise) of planar points.
std::vector<Vec2> convex_hull(std::vector<Vec2> points);
// The hull grown by distance d: its Minkowski sum with a disk, the disk's
// arcs sampled every 15 degrees (still counter-clockwise and convex).
std::vector<Vec2> dilate(const std::vector<Vec2>& hull, double d);

// A star-shaped curve: radius per angle around a centre. Closed curves
// sample [0, 2 pi) uniformly; open ones [start, start + span] including both ends.
struct Radial {
  Vec2 centre = Vec2::Zero();
  bool closed = true;
  double start = 0.0, span = 0.0;
  std::vector<double> r;

  double radius(double angle) const;
  Vec2 point(double angle) const;
  // The curve from angle a0 to a1 (either direction), finely sampled.
  std::vector<Vec2> arc(double a0, double a1) const;
};

// Radial function of a convex hull seen from `centre` (which must lie
// inside or on it), smoothed over `smooth` neighbouring angles.
Radial radial_of(const std::vector<Vec2>& hull, const Vec2& centre, bool closed, double start, double span, int samples,
                 int smooth);

// How a horizontal section is measured.
struct SectionSpec {
  PartMask parts = kAllParts;
  double slab = 0.02;             // points within +-slab of the height
  double ease = 0.01;             // dilation
  int side = 0;                   // +1: only points with x >= 0; 0: all
  bool centre_on_midline = true;  // centre (0, mid z); else the hull's box centre
  // Loose cloth hangs from what is above it: points up to `hang_reach`
  // above the slab count too, drawn in horizontally by `hang` per metre of
  // height (0: off), so a section shrinks gradually below a bulge.
  double hang = 0.0;
  double hang_reach = 0.3;
};
// The section of `env` at height y. Throws layers::Error when the slab is empty.
Radial horizontal_section(const Envelope& env, double y, const SectionSpec& spec);

// Polylines.
double length(const std::vector<body::Vec3>& line);
double length(const std::vector<Vec2>& line);
// n + 1 points uniform in arc length (n segments).
std::vector<body::Vec3> resample(const std::vector<body::Vec3>& line, int n);
// Points at the given arc-length fractions (each in [0, 1]).
std::vector<body::Vec3> resample_at(const std::vector<body::Vec3>& line, const std::vector<double>& fractions);
// Lifts (x, z) points to height y, or (z, y) points to abscissa x.
std::vector<body::Vec3> at_height(const std::vector<Vec2>& xz, double y);
std::vector<body::Vec3> at_abscissa(const std::vector<Vec2>& zy, double x);

// 3 t^2 - 2 t^3 on [0, 1], clamped.
double smooth01(double t);

}  // namespace layers::garment
