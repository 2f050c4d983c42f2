// MGNet's per-sequence derived data (see layout.h).
#include "layers/mgnet/layout.h"

#include <string>

namespace layers::mgnet {

GarmentLayout make_layout(const zoo::SequenceStatic& data, std::int64_t resolution) {
  GarmentLayout out;
  std::vector<UvSplat> splats;
  std::vector<TangentBasis> bases;
  std::vector<at::Tensor> offsets, layer_ids;
  for (std::size_t k = 0; k < data.garments.size(); ++k) {
    const zoo::GarmentStatic& g = data.garments[k];
    const std::string where = "sequence '" + data.id + "' garments[" + std::to_string(k) + "] (" + g.name + ")";
    const std::int64_t n = g.rest.size(0);
    splats.push_back(garment_splat(g, resolution, where));  // throws unless the garment has faces
    bases.push_back(tangent_basis(g.faces, g.uv_faces, g.uv, n));
    const at::Tensor lo = std::get<0>(g.rest.min(0)), hi = std::get<0>(g.rest.max(0));
    offsets.push_back(g.rest - 0.5 * (lo + hi));
    layer_ids.push_back(at::full({1}, static_cast<float>(g.layer), g.rest.options()));
    out.sizes.push_back(n);
  }
  out.splat = concatenate(splats);
  out.basis = concatenate(bases);
  if (!data.garments.empty()) {
    out.rest_offset = at::cat(offsets);
    out.layer = at::cat(layer_ids);
    std::vector<at::Tensor> rest;
    for (const zoo::GarmentStatic& g : data.garments) rest.push_back(g.rest);
    out.rest_normal = vertex_frames(out.basis, at::cat(rest)).select(1, 2);
  }
  return out;
}

}  // namespace layers::mgnet
