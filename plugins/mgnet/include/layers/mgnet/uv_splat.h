// layers/mgnet/uv_splat.h -- garments' UV charts as R x R images: the
// normalised UV points of each garment, their bilinear splat weights, the
// splat (vertices -> image) and the sample (image -> vertices).
//
// UV points: one per distinct (vertex, UV value) pair among the face
// corners, so a vertex on a seam (one UV per panel it belongs to) is
// splatted into every chart it lies on, and what is sampled back for it is
// the mean over its UV points; both sides of a seam thus see the same
// vertex. UVs are normalised to the unit square by the garment's UV
// bounding box, each axis on its own (charts laid side by side fill the
// image instead of a thin strip). Pixel centres sit at (i / (R-1),
// j / (R-1)) (align-corners convention): x = u is the column, y =
// v the row. Several garments are several images (concatenate()).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <ATen/ATen.h>

#include "layers/zoo/model.h"

namespace layers::mgnet {

struct UvSplat {
  std::int64_t resolution = 0;   // R
  std::int64_t images = 0;       // one per garment
  std::int64_t vertices = 0;     // 3D vertices, all garments
  at::Tensor uv;                 // [P,2] normalised UV of each UV point, in [0,1]^2
  at::Tensor vertex;             // [P] int64: the 3D vertex of each UV point
  at::Tensor pixel;              // [P,4] int64: flat pixel index in [0, images R R)
  at::Tensor weight;             // [P,4] float: bilinear weights (each row sums to 1)
  at::Tensor weight_sum;         // [images R R] float: splat weight landing on each pixel
  at::Tensor points_per_vertex;  // [V] float: UV points of each vertex (0 for a vertex in no face)
};

// One garment's UV points and weights (images = 1), on the device of its
// tensors. `where` names the garment in errors: InputError if the UVs its
// faces use span nothing along u or v.
UvSplat garment_splat(const zoo::GarmentStatic& garment, std::int64_t resolution, const std::string& where);

// Garments side by side: images stacked in order, vertex indices offset.
UvSplat concatenate(const std::vector<UvSplat>& parts);

// Per-vertex features [V,C] -> images [images,C,R,R]: each pixel is the
// weighted mean of the features splatted onto it (scatter-add of w f
// divided by the weight sum); pixels nothing lands on are 0.
at::Tensor splat(const UvSplat& s, const at::Tensor& features);

// Share of each pixel covered by the splat, min(weight sum, 1), as
// [images,1,R,R] (an input map telling the network where the chart is).
at::Tensor coverage(const UvSplat& s);

// Images [images,C,R,R] -> per-vertex values [V,C]: bilinear interpolation
// at each UV point (the transpose of the splat gather), averaged over the
// vertex's UV points; 0 for a vertex without any.
at::Tensor sample(const UvSplat& s, const at::Tensor& images);

}  // namespace layers::mgnet
