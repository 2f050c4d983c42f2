// LayersNet's per-sequence topology (see topology.h).
#include "topology.h"

#include <string>

#include "layers/core/error.h"
#include "patches.h"
#include "tokens.h"

namespace layers::layersnet {
namespace {

template <class T>
std::vector<T> to_vector(const at::Tensor& t) {
  const at::Tensor c = t.detach().to(at::kCPU, c10::CppTypeToScalarType<T>::value).contiguous();
  return std::vector<T>(c.data_ptr<T>(), c.data_ptr<T>() + c.numel());
}

PatchInput patch_input(const zoo::GarmentStatic& g) {
  PatchInput in;
  in.n_vertices = g.rest.size(0);
  in.faces = to_vector<std::int64_t>(g.faces);
  in.uv = to_vector<float>(g.uv);
  in.uv_faces = to_vector<std::int64_t>(g.uv_faces);
  in.panel = to_vector<std::int64_t>(g.panel);
  return in;
}

at::Tensor long_tensor(const std::vector<std::int64_t>& v, at::Device device) {
  return at::tensor(v, at::kLong).reshape({-1}).to(device);
}

at::Tensor float_tensor(const std::vector<float>& v, at::Device device) {
  return at::tensor(v, at::kFloat).reshape({-1}).to(device);
}

}  // namespace

at::Tensor patch_mean(const SceneTopology& t, const at::Tensor& v) { return at::mm(t.patch_from_vertex, v); }

at::Tensor vertex_mean(const SceneTopology& t, const at::Tensor& p) { return at::mm(t.vertex_from_patch, p); }

SceneTopology build_topology(const zoo::SequenceStatic& s, double patch_size) {
  const at::Device device = s.garments.empty() ? at::Device(at::kCPU) : s.garments[0].rest.device();
  SceneTopology t;
  t.vertex_offset = {0};
  t.patch_offset = {0};
  std::vector<std::int64_t> member_vertex, member_patch, edge_a, edge_b, token_of_garment;
  std::vector<float> patch_weight, vertex_weight, kind;
  std::vector<std::vector<float>> tokens;  // distinct raw attribute vectors

  for (std::size_t k = 0; k < s.garments.size(); ++k) {
    const zoo::GarmentStatic& g = s.garments[k];
    const std::string what = "sequence '" + s.id + "' garments[" + std::to_string(k) + "] (" + g.name + ")";
    if (g.faces.size(0) == 0) throw InputError(what, "faces", "at least one face (patches are made of faces)", "none");
    const std::int64_t vo = t.vertex_offset.back(), po = t.patch_offset.back();
    const GarmentPatches gp = build_patches(patch_input(g), patch_size, what);

    std::vector<std::int64_t> patches_of(g.rest.size(0), 0);
    for (std::int64_t v : gp.members) ++patches_of[v];
    for (std::int64_t p = 0; p < gp.size(); ++p) {
      const float n = static_cast<float>(gp.offsets[p + 1] - gp.offsets[p]);
      for (std::int64_t i = gp.offsets[p]; i < gp.offsets[p + 1]; ++i) {
        member_vertex.push_back(vo + gp.members[i]);
        member_patch.push_back(po + p);
        patch_weight.push_back(1.0f / n);
        vertex_weight.push_back(1.0f / static_cast<float>(patches_of[gp.members[i]]));
      }
      kind.insert(kind.end(), {g.layer == 0 ? 1.0f : 0.0f, g.layer == 0 ? 0.0f : 1.0f, 0.0f});
    }
    for (const auto& [a, b] : gp.mesh_edges) {
      edge_a.push_back(po + a);
      edge_b.push_back(po + b);
    }

    const std::int64_t n_attr = g.attributes.size(0);
    if (n_attr != 0 && n_attr != kAttributes)
      throw InputError(what, "attributes",
                       "7 values (mass, tension, compression, shear, bending, friction, self_friction) or none",
                       std::to_string(n_attr) + " values");
    std::int64_t token = -1;
    if (n_attr == kAttributes) {
      const std::vector<float> raw = to_vector<float>(g.attributes);
      for (std::size_t i = 0; i < tokens.size() && token < 0; ++i)
        if (tokens[i] == raw) token = static_cast<std::int64_t>(i);
      if (token < 0) {
        token = static_cast<std::int64_t>(tokens.size());
        tokens.push_back(raw);
      }
    }
    token_of_garment.push_back(token);
    t.vertex_offset.push_back(vo + g.rest.size(0));
    t.patch_offset.push_back(po + gp.size());
  }

  const std::int64_t P = t.patches(), V = t.vertices(), T = static_cast<std::int64_t>(tokens.size());
  const at::Tensor vertex = long_tensor(member_vertex, at::kCPU), patch = long_tensor(member_patch, at::kCPU);
  t.patch_from_vertex = at::sparse_coo_tensor(at::stack({patch, vertex}), float_tensor(patch_weight, at::kCPU), {P, V})
                            .coalesce()
                            .to(device);
  t.vertex_from_patch = at::sparse_coo_tensor(at::stack({vertex, patch}), float_tensor(vertex_weight, at::kCPU), {V, P})
                            .coalesce()
                            .to(device);
  t.memberships = vertex.numel();
  t.patch_kind = float_tensor(kind, device).reshape({P, 3});

  at::Tensor mesh = at::zeros({P, P}, at::kBool);
  const at::Tensor a = long_tensor(edge_a, at::kCPU), b = long_tensor(edge_b, at::kCPU);
  mesh.index_put_({a, b}, true);
  mesh.index_put_({b, a}, true);
  t.mesh_mask = mesh.to(device);
  t.mesh_edges = static_cast<std::int64_t>(edge_a.size());

  std::vector<float> flat;
  for (const auto& v : tokens) flat.insert(flat.end(), v.begin(), v.end());
  t.attributes = scale_attributes(float_tensor(flat, device).reshape({T, kAttributes}));
  at::Tensor owns = at::zeros({P, T}, at::kBool);
  for (std::size_t k = 0; k < s.garments.size(); ++k)
    if (token_of_garment[k] >= 0)
      owns.narrow(0, t.patch_offset[k], t.patch_offset[k + 1] - t.patch_offset[k])
          .select(1, token_of_garment[k])
          .fill_(true);
  t.patch_attribute = owns.to(device);
  return t;
}

}  // namespace layers::layersnet
