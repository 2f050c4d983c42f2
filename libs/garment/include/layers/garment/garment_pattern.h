// layers/garment/garment_pattern.h -- sewing patterns and their assembly.
//
// A template describes each panel as a structured grid of 3D points placed
// around the body (rows x columns, e.g. one row per horizontal section of
// a bodice). The flat panel is the grid developed into the plane as rigidly
// as possible (ARAP, started from arc-length coordinates), so lengths and
// areas in 2D match the placed panel up to its curvature; those
// coordinates, in metres, are the panel's UVs. sew() samples every outline edge at the
// target edge length (both sides of a seam get the same count), meshes each
// flat panel (garment_triangulate.h), lifts the points onto the grid's 3D
// surface and merges the 3D vertices of matching seam samples. UV
// vertices stay per panel (a seam duplicates UV vertices, not 3D ones).
// Faces are wound counter-clockwise in UV and outward in 3D.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "layers/body/rotation.h"
#include "layers/geometry/mesh.h"
#include "layers/geometry/nearest.h"

namespace layers::garment {

// One panel placed in 3D as a rows x cols grid (row-major).
struct PanelGrid {
  std::string name;
  int rows = 0, cols = 0;
  std::vector<body::Vec3> points;

  PanelGrid() = default;
  PanelGrid(std::string n, int r, int c)
      : name(std::move(n)), rows(r), cols(c), points(static_cast<std::size_t>(r) * c) {}
  body::Vec3& at(int i, int j) { return points[static_cast<std::size_t>(i) * cols + j]; }
  const body::Vec3& at(int i, int j) const { return points[static_cast<std::size_t>(i) * cols + j]; }
};

// Grid sides: Bottom = row 0, Top = last row (indexed by column), Left =
// column 0, Right = last column (indexed by row).
enum class Side { Bottom, Right, Top, Left };

// The grid points of one side of a panel from index `from` to index `to`
// (either direction; the direction matters for seams).
struct Edge {
  int panel = 0;
  Side side = Side::Bottom;
  int from = 0, to = 0;
};

// Two edges sewn together: a's `from` end meets b's `from` end.
struct Seam {
  Edge a, b;
};

struct Pattern {
  std::vector<PanelGrid> panels;
  std::vector<Seam> seams;
  std::vector<Edge> openings;  // free boundary (hems, cuffs, neckline, ...)

  int add(PanelGrid grid) {
    panels.push_back(std::move(grid));
    return static_cast<int>(panels.size()) - 1;
  }
  // Every side of every panel must be covered exactly once by seams and
  // openings; sew() checks.
  void sew(Edge a, Edge b) { seams.push_back({a, b}); }
  void open(Edge e) { openings.push_back(e); }
};

using UVs = Eigen::Matrix<float, Eigen::Dynamic, 2, Eigen::RowMajor>;

// A garment mesh in the layout of LAYERS-H5 (`garments/<k>/`).
struct GarmentMesh {
  std::string type;
  int layer = 0;              // 0 inner, 1 outer
  geometry::Points vertices;  // [V,3] placed around the T-pose body; also the rest shape
  geometry::Faces faces;      // [F,3] outward, consistently wound
  UVs uv;                     // [U,2] panel coordinates in metres (panels laid side by side)
  geometry::Faces uv_faces;   // [F,3] into uv
  Eigen::VectorXi panel;      // [F] panel id of each face
  std::vector<std::string> panel_names;
  std::vector<std::uint8_t> boundary;  // [V] 1 on an opening (hem, cuff, neckline, ...)
  // The sampled sizes (ease, lengths, ...) in metres or as fractions.
  std::vector<std::pair<std::string, double>> style;

  int num_vertices() const { return static_cast<int>(vertices.rows()); }
  int num_faces() const { return static_cast<int>(faces.rows()); }
  geometry::TriMesh mesh() const { return {vertices, faces}; }
  double style_value(const std::string& key) const;  // NaN when absent
};

// Flattens a grid (see the file comment): one UV per grid point, the first
// row along +u.
std::vector<Eigen::Vector2d> develop(const PanelGrid& grid);

// Assembles the garment at target edge length `h`. `body` (the skin
// points) tells which side of each panel faces outwards. Throws
// layers::Error on an inconsistent pattern.
GarmentMesh sew(const Pattern& pattern, double h, const geometry::PointIndex& body);

// Lifting a flat panel onto its 3D grid can flatten a triangle whose
// corners all lie on a straight stretch of a 3D outline (three samples of
// a neckline that is curved in UV but straight across the back), or lift
// two corners onto one point where grid rows meet: its 3D area is then a
// tiny share of its UV area. Each such face (3D area under a tenth of its
// UV area) gets its longest edge flipped, when that edge is inside one
// panel and the flip leaves both faces larger in 3D and not inverted in
// UV; what remains has its corners that are not on an opening relaxed
// towards their neighbours. Returns the number of repairs.
int repair_slivers(GarmentMesh& mesh);

}  // namespace layers::garment
