// plugins/layersnet/src/patches.h -- LayersNet's patches of one garment from
// its UV charts, torch-free: per sewing panel, a face joins the patch
// floor(uv_centroid / patch_size); a vertex belongs to the patches of its
// faces; empty patches never exist (patches come from faces). Mesh edges
// E^M join two patches when a mesh edge joins a vertex of one to a vertex
// of the other (a vertex shared by both counts: its edges reach both).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace layers::layersnet {

// One garment's topology, as flat row-major arrays.
struct PatchInput {
  std::int64_t n_vertices = 0;
  std::vector<std::int64_t> faces;     // [F,3] vertex indices
  std::vector<float> uv;               // [U,2]
  std::vector<std::int64_t> uv_faces;  // [F,3] indices into uv
  std::vector<std::int64_t> panel;     // [F]
};

struct GarmentPatches {
  // Patch p is UV cell (cell[p][1], cell[p][2]) of panel cell[p][0];
  // patches are sorted by (panel, cell u, cell v).
  std::vector<std::array<std::int64_t, 3>> cell;
  // Vertices of patch p: members[offsets[p] .. offsets[p+1]), ascending.
  std::vector<std::int64_t> offsets, members;
  // E^M: patch pairs (a, b), a < b, sorted, each once.
  std::vector<std::pair<std::int64_t, std::int64_t>> mesh_edges;

  std::int64_t size() const { return static_cast<std::int64_t>(cell.size()); }
};

// Builds the patches. `what` names the garment in errors (InputError for
// inconsistent sizes, indices out of range, non-finite UVs, a patch size
// that is not positive or UV cells beyond +-2^40).
GarmentPatches build_patches(const PatchInput& in, double patch_size, const std::string& what);

}  // namespace layers::layersnet
