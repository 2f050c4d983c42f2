// layers/garment/garment_tube.h -- rows of horizontal sections shared by the
// tube and top pieces: each row is a section of the envelope at one height,
// cut at given angles (knots) into segments that are resampled by arc
// length to the same number of columns in every row, so that the knots
// (sides, centre lines, neckline ends) are grid columns.
#pragma once

#include <string>
#include <vector>

#include "layers/garment/garment_pieces.h"
#include "layers/garment/garment_section.h"

namespace layers::garment {

struct TubeRows {
  std::vector<std::vector<body::Vec3>> front, back;  // [row][column]
  std::vector<int> front_knot_cols, back_knot_cols;  // column of each knot
  std::vector<Radial> sections;                      // per row
};

// Front rows run along the knot angles `front_knots` (e.g. pi -> pi/2 -> 0:
// right side, centre front, left side), back rows along `back_knots`.
// Columns are spread uniformly by arc length within each segment, or, with
// weight x_uniform(y) -> 1, uniformly in x (a top row that shoulder
// columns rise from must not crowd columns into one x around the sides).
TubeRows tube_rows(const FitContext& ctx, const std::vector<double>& heights, const EaseProfile& ease,
                   const EaseProfile& hang, const std::vector<double>& front_knots,
                   const std::vector<double>& back_knots, const std::vector<double>& x_uniform = {});

// How torso rows are measured at height y (parts, ease, hang); the ease
// is at least ctx.room's there.
SectionSpec torso_section(const FitContext& ctx, double y, const EaseProfile& ease, const EaseProfile& hang);

// Heights from y0 to y1 (both included) at about `step` spacing, at least 3.
std::vector<double> row_heights(double y0, double y1, double step);

// A grid from rows of equal length.
PanelGrid grid_of(const std::string& name, const std::vector<std::vector<body::Vec3>>& rows);

}  // namespace layers::garment
