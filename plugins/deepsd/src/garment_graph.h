// plugins/deepsd/src/garment_graph.h -- the mesh graph DeePSD's descriptor
// layers run on: each vertex's mesh neighbours (vertices sharing a face
// edge) as directed edge lists, and the mean over them.
#pragma once

#include <ATen/ATen.h>

#include <cstdint>

namespace layers::deepsd {

struct GarmentGraph {
  at::Tensor src, dst;    // [E] int64: an edge src -> dst for each direction of each mesh edge
  at::Tensor inv_degree;  // [V,1] float: 1 / neighbours of each vertex (0 when it has none)
  std::int64_t vertices = 0;
};

// The graph of a triangle mesh (faces [F,3], indices < vertices), on the
// faces' device.
GarmentGraph mesh_graph(const at::Tensor& faces, std::int64_t vertices);

// Mean of h [V,C] over each vertex's neighbours ([V,C], zero for a vertex
// without any); differentiable in h.
at::Tensor mean_over_neighbours(const at::Tensor& h, const GarmentGraph& graph);

}  // namespace layers::deepsd
