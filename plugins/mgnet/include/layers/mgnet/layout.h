// layers/mgnet/layout.h -- what MGNet derives once per sequence from the
// static data: all garments' UV splats (one image each) and tangent bases,
// concatenated in garment order, plus the rest-shape maps and each
// garment's layer (the garment-type-free identifier the shared weights see).
#pragma once

#include <cstdint>
#include <vector>

#include <ATen/ATen.h>

#include "layers/mgnet/tangent_frames.h"
#include "layers/mgnet/uv_splat.h"
#include "layers/zoo/model.h"

namespace layers::mgnet {

struct GarmentLayout {
  UvSplat splat;                    // images = garments, vertices = all garments' vertices
  TangentBasis basis;               // the same vertices
  std::vector<std::int64_t> sizes;  // vertices of each garment
  at::Tensor rest_offset;           // [V,3] rest position minus the centre of its garment's rest bounding box
  at::Tensor rest_normal;           // [V,3] normal of the rest frame
  at::Tensor layer;                 // [G] float: 0 inner, 1 outer
};

// From prepared (validated, converted) static data; InputError (naming the
// sequence and garment) for a garment whose UVs span nothing.
GarmentLayout make_layout(const zoo::SequenceStatic& data, std::int64_t resolution);

}  // namespace layers::mgnet
