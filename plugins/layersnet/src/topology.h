// plugins/layersnet/src/topology.h -- what LayersNet derives once per sequence
// from the static data: all garments' patches in one index space
// (garment after garment), the vertex<->patch memberships used to scatter
// and gather means, the mesh-edge mask E^M, each patch's layer, and the
// attribute tokens (one per distinct attribute vector).
#pragma once

#include <cstdint>
#include <vector>

#include <ATen/ATen.h>

#include "layers/zoo/model.h"

namespace layers::layersnet {

struct SceneTopology {
  std::vector<std::int64_t> vertex_offset;  // [garments + 1]: garment k owns vertices [o_k, o_k+1)
  std::vector<std::int64_t> patch_offset;   // [garments + 1], likewise for patches
  // The means over the vertex<->patch memberships as sparse (COO,
  // coalesced) matrices: patch p = sum of its vertices / their count,
  // vertex v = sum of its patches / their count. One sparse product each
  // (5x faster than gather + scatter-add on 32k vertices x 128 channels).
  at::Tensor patch_from_vertex;  // [P,V]
  at::Tensor vertex_from_patch;  // [V,P]
  std::int64_t memberships = 0;  // (vertex, patch) pairs
  at::Tensor mesh_mask;          // [P,P] bool E^M (symmetric, empty diagonal)
  std::int64_t mesh_edges = 0;   // undirected E^M edges
  at::Tensor patch_kind;         // [P,3] one-hot: inner garment, outer garment, body
  at::Tensor attributes;         // [T,7] distinct attribute vectors, min-max scaled
  at::Tensor patch_attribute;    // [P,T] bool: the patch's garment has token t

  std::int64_t vertices() const { return vertex_offset.back(); }
  std::int64_t patches() const { return patch_offset.back(); }
};

// Mean over each patch's vertices: [V,c] -> [P,c].
at::Tensor patch_mean(const SceneTopology& t, const at::Tensor& per_vertex);
// Mean over each vertex's patches: [P,c] -> [V,c] (0 for a vertex in no face).
at::Tensor vertex_mean(const SceneTopology& t, const at::Tensor& per_patch);

// Builds it on the device of the sequence's tensors (as Model::prepare
// converted them). Throws InputError naming the sequence and garment for a
// garment without faces or an attribute vector that is neither empty nor
// the 7 values of layers/zoo/model.h.
SceneTopology build_topology(const zoo::SequenceStatic& s, double patch_size);

}  // namespace layers::layersnet
