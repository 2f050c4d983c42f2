// LayersNet patches from UV charts (see patches.h).
#include "patches.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "layers/core/error.h"

namespace layers::layersnet {
namespace {

void check_indices(const std::vector<std::int64_t>& idx, std::int64_t bound, const std::string& what,
                   const std::string& field) {
  for (std::int64_t i : idx) {
    if (i < 0 || i >= bound)
      throw InputError(what, field, "indices in [0, " + std::to_string(bound) + ")", std::to_string(i));
  }
}

void check_input(const PatchInput& in, double patch_size, const std::string& what) {
  if (!(patch_size > 0) || !std::isfinite(patch_size))
    throw InputError(what, "patch_size", "a positive number", std::to_string(patch_size));
  if (in.faces.size() % 3 != 0) throw InputError(what, "faces", "[F,3]", std::to_string(in.faces.size()) + " values");
  if (in.uv.size() % 2 != 0) throw InputError(what, "uv", "[U,2]", std::to_string(in.uv.size()) + " values");
  const std::size_t nf = in.faces.size() / 3;
  if (in.uv_faces.size() != nf * 3)
    throw InputError(what, "uv_faces", "[" + std::to_string(nf) + ",3]",
                     std::to_string(in.uv_faces.size()) + " values");
  if (in.panel.size() != nf)
    throw InputError(what, "panel", "[" + std::to_string(nf) + "]", std::to_string(in.panel.size()) + " values");
  check_indices(in.faces, in.n_vertices, what, "faces");
  check_indices(in.uv_faces, static_cast<std::int64_t>(in.uv.size() / 2), what, "uv_faces");
  for (float x : in.uv)
    if (!std::isfinite(x)) throw InputError(what, "uv", "finite values", "NaN or infinity");
}

std::int64_t cell_of(double x, double patch_size, const std::string& what) {
  const double c = std::floor(x / patch_size);
  if (std::abs(c) > 1099511627776.0)  // 2^40
    throw InputError(what, "uv", "UV cells within +-2^40 patch sizes", "a UV coordinate of " + std::to_string(x));
  return static_cast<std::int64_t>(c);
}

}  // namespace

GarmentPatches build_patches(const PatchInput& in, double patch_size, const std::string& what) {
  check_input(in, patch_size, what);
  const std::size_t nf = in.faces.size() / 3;

  // Patch key of every face; keys sorted give the patch order.
  std::vector<std::array<std::int64_t, 3>> face_key(nf);
  std::map<std::array<std::int64_t, 3>, std::int64_t> index;
  for (std::size_t f = 0; f < nf; ++f) {
    double u = 0, v = 0;
    for (int k = 0; k < 3; ++k) {
      const std::int64_t t = in.uv_faces[3 * f + k];
      u += in.uv[2 * t];
      v += in.uv[2 * t + 1];
    }
    face_key[f] = {in.panel[f], cell_of(u / 3, patch_size, what), cell_of(v / 3, patch_size, what)};
    index.emplace(face_key[f], 0);
  }
  GarmentPatches out;
  for (auto& [key, p] : index) {
    p = out.size();
    out.cell.push_back(key);
  }

  // Memberships: sorted unique (patch, vertex) pairs.
  std::vector<std::pair<std::int64_t, std::int64_t>> pv;
  pv.reserve(3 * nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const std::int64_t p = index.at(face_key[f]);
    for (int k = 0; k < 3; ++k) pv.emplace_back(p, in.faces[3 * f + k]);
  }
  std::sort(pv.begin(), pv.end());
  pv.erase(std::unique(pv.begin(), pv.end()), pv.end());
  out.offsets.assign(out.cell.size() + 1, 0);
  for (const auto& [p, v] : pv) {
    ++out.offsets[p + 1];
    out.members.push_back(v);
  }
  for (std::size_t p = 0; p < out.cell.size(); ++p) out.offsets[p + 1] += out.offsets[p];

  // Patches of each vertex (CSR), then E^M over the mesh edges of faces.
  std::vector<std::int64_t> vstart(in.n_vertices + 1, 0), vpatch(pv.size());
  for (const auto& [p, v] : pv) ++vstart[v + 1];
  for (std::int64_t v = 0; v < in.n_vertices; ++v) vstart[v + 1] += vstart[v];
  std::vector<std::int64_t> fill(vstart.begin(), vstart.end() - 1);
  for (const auto& [p, v] : pv) vpatch[fill[v]++] = p;

  std::vector<std::pair<std::int64_t, std::int64_t>> edges;
  auto join = [&](std::int64_t a, std::int64_t b) {
    for (std::int64_t i = vstart[a]; i < vstart[a + 1]; ++i)
      for (std::int64_t j = vstart[b]; j < vstart[b + 1]; ++j) {
        const std::int64_t pa = vpatch[i], pb = vpatch[j];
        if (pa != pb) edges.emplace_back(std::min(pa, pb), std::max(pa, pb));
      }
  };
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) join(in.faces[3 * f + k], in.faces[3 * f + (k + 1) % 3]);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  out.mesh_edges = std::move(edges);
  return out;
}

}  // namespace layers::layersnet
