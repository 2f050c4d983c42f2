// layers/report/mesh_view.h -- triangle meshes seen orthographically from
// the front (the camera on +z looking down -z, y up: screen x = world x,
// screen y = world y), as flat-shaded polygons for gnuplot.
//
// Each face is shaded by its unit normal's z (facing the camera = full
// colour, edge-on = darker) and the triangles are written farthest first
// (painter's algorithm on the centroid depth), so that gnuplot, which
// fills polygons in file order, draws nearer faces over farther ones.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace layers::report {

struct ScreenTriangle {
  float x[3], y[3];
  float depth;        // centroid z: larger is nearer the camera
  std::uint32_t rgb;  // 0xRRGGBB after shading
};

struct ScreenBounds {
  double xmin = 0, xmax = 0, ymin = 0, ymax = 0;
  bool empty = true;
  void add(double x, double y);
  void add(const ScreenBounds& other);
};

// `base_rgb` scaled by (ambient + (1 - ambient) * |nz|).
std::uint32_t shade(std::uint32_t base_rgb, double nz, double ambient = 0.4);

// Appends the faces of a mesh (positions [V,3] metres, faces [F,3]).
// With `cull_back`, faces whose normal points away from the camera are
// dropped (closed meshes such as the body; garments keep both sides).
// Degenerate faces and faces with a non-finite vertex are skipped.
// `depth_bias` (metres) moves the faces' sort depth toward the camera: a
// garment a few millimetres outside the skin has larger triangles than the
// body, whose centroids can sort behind the skin's and let it show
// through; a bias of a few centimetres per layer keeps body < inner <
// outer where they overlap, while a limb well in front still covers them.
// Throws layers::Error for a face index out of range.
void add_mesh(std::vector<ScreenTriangle>& out, const float* positions, std::int64_t n_vertices,
              const std::vector<std::int32_t>& faces, std::uint32_t base_rgb, bool cull_back, float depth_bias = 0.0f);

// Screen bounds of the finite vertices of a mesh.
ScreenBounds mesh_bounds(const float* positions, std::int64_t n_vertices);

// The triangles as a gnuplot data file, farthest first: one polygon per
// block of three "x y rgb" lines, blocks separated by a blank line (plot
// with `filledcurves closed fillcolor rgb variable`).
std::string polygon_data(std::vector<ScreenTriangle> triangles);

}  // namespace layers::report
