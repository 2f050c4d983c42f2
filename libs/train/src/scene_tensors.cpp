// LAYERS-H5 arrays -> model tensors (see scene_tensors.h).
#include "layers/train/scene_tensors.h"

#include <array>

#include "layers/core/error.h"

namespace layers::train {
namespace {

// The order of zoo::GarmentStatic::attributes (docs/format.md "Garment
// attributes").
constexpr std::array<const char*, 7> kAttributeOrder = {"mass",    "tension",  "compression",  "shear",
                                                        "bending", "friction", "self_friction"};

template <class T>
at::Tensor tensor_of(const std::vector<T>& values, std::vector<std::int64_t> sizes, at::ScalarType type) {
  // from_blob does not own the memory: clone into a tensor that does.
  return at::from_blob(const_cast<T*>(values.data()), sizes, at::TensorOptions().dtype(type)).clone();
}

at::Tensor ints(const std::vector<std::int32_t>& v, std::vector<std::int64_t> sizes) {
  return tensor_of(v, std::move(sizes), at::kInt).to(at::kLong);
}
at::Tensor floats(const std::vector<float>& v, std::vector<std::int64_t> sizes) {
  return tensor_of(v, std::move(sizes), at::kFloat);
}

at::Tensor attributes_of(const data::GarmentStatic& g, const std::string& seq) {
  std::vector<float> values;
  for (const char* name : kAttributeOrder) {
    auto it = g.attributes.find(name);
    if (it == g.attributes.end())
      throw InputError("sequence '" + seq + "'", "garments/" + g.name + " attribute " + name,
                       "the seven garment attributes", "no '" + std::string(name) + "'");
    values.push_back(static_cast<float>(it->second));
  }
  return at::tensor(values, at::kFloat);
}

}  // namespace

std::vector<std::size_t> GarmentSelection::pick(const std::vector<data::GarmentStatic>& garments) const {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < garments.size(); ++k)
    if (!inner_only || garments[k].layer == 0) out.push_back(k);
  return out;
}

zoo::SequenceStatic to_model_static(const data::SequenceStatic& s, const GarmentSelection& selection) {
  zoo::SequenceStatic out;
  out.id = selection.inner_only ? s.id + "#inner" : s.id;
  const data::BodyStatic& b = s.body;
  out.body_faces = ints(b.faces, {b.n_faces(), 3});
  if (b.n_joints() > 0) out.joint_parents = ints(b.joint_parents, {b.n_joints()});
  if (b.n_vertices() > 0) {
    out.skin_index = ints(b.skin_index, {b.n_vertices(), 4});
    out.skin_weight = floats(b.skin_weight, {b.n_vertices(), 4});
  }
  if (!b.tpose_joints.empty()) out.tpose_joints = floats(b.tpose_joints, {b.n_joints(), 3, 4});
  for (std::size_t k : selection.pick(s.garments)) {
    const data::GarmentStatic& g = s.garments[k];
    zoo::GarmentStatic z;
    z.name = g.name;
    z.type = g.type;
    z.layer = g.layer;
    z.faces = ints(g.faces, {g.n_faces(), 3});
    z.rest = floats(g.rest, {g.n_vertices(), 3});
    z.uv = floats(g.uv, {g.n_uv(), 2});
    z.uv_faces = ints(g.uv_faces, {g.n_faces(), 3});
    z.panel = ints(g.panel, {g.n_faces()});
    z.attributes = attributes_of(g, s.id);
    out.garments.push_back(std::move(z));
  }
  if (out.garments.empty())
    throw InputError("sequence '" + s.id + "'", "garments", "at least one garment to model", "none selected");
  return out;
}

FrameTensors to_frame_tensors(const data::Window& w, const std::vector<data::GarmentStatic>& garments,
                              const GarmentSelection& selection) {
  FrameTensors f;
  const std::int64_t n = w.n_frames;
  f.first_frame = w.first_frame;
  const auto per_frame = [&](std::size_t size) {
    return static_cast<std::int64_t>(size) / std::max<std::int64_t>(n, 1);
  };
  f.body = floats(w.body.positions, {n, per_frame(w.body.positions.size()) / 3, 3});
  f.root = floats(w.body.root, {n, 3});
  f.root_rot = floats(w.body.root_rot, {n, 4});
  if (!w.body.joints.empty()) f.joints = floats(w.body.joints, {n, per_frame(w.body.joints.size()) / 12, 3, 4});
  f.wind_rotation = floats(w.wind.rotation, {n, 4});
  f.wind_strength = floats(w.wind.strength, {n});
  for (std::size_t k : selection.pick(garments)) {
    const std::vector<float>& p = w.garments.at(k);
    f.garments.push_back(floats(p, {n, per_frame(p.size()) / 3, 3}));
  }
  return f;
}

std::vector<zoo::GarmentState> true_states(const FrameTensors& f, std::int64_t i) {
  std::vector<zoo::GarmentState> states;
  for (const at::Tensor& g : f.garments) states.push_back({g[i - 1], g[i]});
  return states;
}

zoo::StepInput step_input(const FrameTensors& f, std::int64_t i, std::vector<zoo::GarmentState> states) {
  if (i < 1 || i + 1 >= f.frames())
    throw Error("step_input: row " + std::to_string(i) + " needs rows i-1 and i+1 in a window of " +
                std::to_string(f.frames()) + " frames");
  zoo::StepInput in;
  in.garments = std::move(states);
  in.body = f.body[i];
  in.body_next = f.body[i + 1];
  in.root = f.root.slice(0, i - 1, i + 2);
  in.root_rot = f.root_rot.slice(0, i - 1, i + 2);
  in.wind_rotation = f.wind_rotation.slice(0, i, i + 2);
  in.wind_strength = f.wind_strength.slice(0, i, i + 2);
  if (f.joints.defined()) {
    in.joints = f.joints[i];
    in.joints_next = f.joints[i + 1];
  }
  return in;
}

FrameTensors to_device(const FrameTensors& f, const at::Device& device) {
  FrameTensors out = f;
  const auto move = [&](const at::Tensor& t) { return t.defined() ? t.to(device) : t; };
  out.body = move(f.body);
  out.root = move(f.root);
  out.root_rot = move(f.root_rot);
  out.joints = move(f.joints);
  out.wind_rotation = move(f.wind_rotation);
  out.wind_strength = move(f.wind_strength);
  for (at::Tensor& g : out.garments) g = move(g);
  return out;
}

}  // namespace layers::train
