// layers/garment/garment_triangulate.h -- meshing of one flat sewing-pattern
// panel: a simple polygon (the panel outline with its seam samples) is
// filled with points of an equilateral lattice of the target edge length
// and triangulated (constrained Delaunay: the outline edges are kept, the
// rest satisfies the empty-circle rule), then lightly smoothed. Used by
// the garment templates; independent of the body and of 3D.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

namespace layers::garment {

using Vec2 = Eigen::Vector2d;

struct PlanarMesh {
  // The outline points first (in the order given), then interior points.
  std::vector<Vec2> points;
  // Counter-clockwise triangles (indices into points).
  std::vector<std::array<int, 3>> triangles;
  int num_boundary = 0;
};

// Twice the signed area of a polygon (positive when counter-clockwise).
double signed_area2(const std::vector<Vec2>& polygon);

// Meshes the simple polygon `outline` (counter-clockwise, no repeated
// points, no self-intersections) at target edge length `h`: lattice points
// closer than `margin` * h to the outline are dropped, the rest are
// inserted, and `smoothing` rounds of Laplacian smoothing (each followed by
// Delaunay edge flips) even out the triangles near the outline. Throws
// layers::Error when the outline is not a valid simple polygon.
PlanarMesh mesh_polygon(const std::vector<Vec2>& outline, double h, int smoothing = 3, double margin = 0.6);

}  // namespace layers::garment
