// MGNet's per-step input maps (see input_maps.h).
#include "layers/mgnet/input_maps.h"

#include <string>
#include <vector>

#include "layers/core/error.h"
#include "layers/mgnet/body_seeds.h"
#include "layers/zoo/rotations.h"

namespace layers::mgnet {
namespace {

// Wind strength at which the paper's (Blender) wind is 1.
constexpr double kWindScale = 400.0;

// Inputs may be any floating type; the network runs in float32.
at::Tensor f32(const at::Tensor& t) { return t.to(at::kFloat); }

at::Tensor cat_states(const zoo::StepInput& in, bool current) {
  std::vector<at::Tensor> parts;
  for (const zoo::GarmentState& g : in.garments) parts.push_back(f32(current ? g.current : g.prev));
  return at::cat(parts);
}

}  // namespace

StepMaps step_maps(const GarmentLayout& layout, const zoo::StepInput& in, const zoo::Normalization& norm, Base base) {
  const at::Tensor roots = f32(in.root), body = f32(in.body), body_next = f32(in.body_next);
  const at::Tensor root_prev = roots[0], root = roots[1], root_next = roots[2];
  const at::Tensor current = cat_states(in, true);
  const at::Tensor rel = current - root, rel_prev = cat_states(in, false) - root_prev;
  const at::Tensor v = rel - rel_prev;
  const at::Tensor seed = nearest_body_vertex(body, current);
  const at::Tensor seed_next = body_next.index_select(0, seed) - root_next;
  const at::Tensor seed_velocity = seed_next - (body.index_select(0, seed) - root);
  const at::Tensor base_rel = rel + (base == Base::body_seeds ? seed_velocity : v);

  StepMaps out;
  out.base = base_rel + root_next;
  out.frames = vertex_frames(layout.basis, rel);  // frames do not depend on the translation
  const at::Tensor state_vertex =
      at::cat({norm.garment_position.normalize(rel), norm.garment_position.scale(layout.rest_offset),
               layout.rest_normal, out.frames.select(1, 2)},
              1);
  const at::Tensor dynamic_vertex =
      at::cat({norm.garment_position.normalize(rel_prev), norm.garment_velocity.normalize(v),
               norm.garment_acceleration.scale(seed_velocity - v), norm.garment_position.scale(seed_next - base_rel),
               norm.body_velocity.normalize(seed_velocity)},
              1);
  // One splat for both encoders' vertex features.
  const at::Tensor images = splat(layout.splat, at::cat({state_vertex, dynamic_vertex}, 1));
  const std::int64_t G = layout.splat.images, R = layout.splat.resolution, ns = state_vertex.size(1);
  const at::Tensor cover = coverage(layout.splat);
  const at::Tensor layer = layout.layer.reshape({G, 1, 1, 1}).expand({G, 1, R, R});
  const at::Tensor global =
      at::cat({(f32(in.wind_strength[1]) / kWindScale).reshape({1}), zoo::rotate_z(f32(in.wind_rotation[1])),
               norm.garment_velocity.scale(root_next - root),
               norm.garment_acceleration.scale(root_next - 2 * root + root_prev)});
  const at::Tensor global_maps = global.reshape({1, -1, 1, 1}).expand({G, global.size(0), R, R});
  out.state = at::cat({images.narrow(1, 0, ns), cover, layer}, 1);
  out.dynamic = at::cat({images.narrow(1, ns, dynamic_vertex.size(1)), cover, global_maps}, 1);
  if (out.state.size(1) != kStateChannels || out.dynamic.size(1) != kDynamicChannels)
    throw Error("mgnet: input maps have " + std::to_string(out.state.size(1)) + " + " +
                std::to_string(out.dynamic.size(1)) + " channels, the encoders expect " +
                std::to_string(kStateChannels) + " + " + std::to_string(kDynamicChannels));
  return out;
}

}  // namespace layers::mgnet
