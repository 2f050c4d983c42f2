// The LayersNet model: per-step graph, encoders, processor, decoder and
// integration (see layersnet.h and docs/layersnet.md).
#include "layersnet.h"

#include <algorithm>
#include <mutex>

#include "body_contacts.h"
#include "decoder.h"
#include "frame.h"
#include "joint_binding.h"
#include "tokens.h"
#include "topology.h"
#include "layers/core/error.h"
#include "layers/zoo/joint_motion.h"

namespace layers::layersnet {
namespace {

constexpr std::int64_t kState = 6;      // normalised position, velocity
constexpr std::int64_t kKinds = 3;      // inner garment, outer garment, body
constexpr std::int64_t kNearBody = 10;  // body state, offset / radius, present

}  // namespace

struct LayersNet::Cached : Derived {
  SceneTopology topology;
  // Bases "bones" (bound at derive) and "skin" (bound on the sequence's
  // first step: it needs a body frame), hence mutable.
  mutable JointBinding joints;
  mutable std::once_flag skin_bound;
};

LayersNet::LayersNet(const Params& params)
    : Model(kName), params_(params), base_(base_from_name(params.base)), learned_blend_(params.blend == "learned") {
  const std::int64_t d = params.width;
  encode_state_ = register_module("encode_state", std::make_shared<Mlp>(kState + kKinds, d, d, 1));
  encode_attributes_ = register_module("encode_attributes", std::make_shared<Mlp>(kAttributes, d, d, 1));
  encode_wind_ = register_module("encode_wind", std::make_shared<Mlp>(kWindFeatures, d, d, 1));
  decoder_ = register_module("decoder", std::make_shared<Decoder>(kState + kNearBody, d, learned_blend_ ? 4 : 3));
  gravity_ = register_parameter("gravity", at::randn({1, d}) * 0.1);
  for (std::int64_t b = 0; b < params.blocks; ++b)
    blocks_.push_back(register_module("block" + std::to_string(b), std::make_shared<TieBlock>(d, params.heads)));
}

LayersNet::~LayersNet() = default;

cfg::Node LayersNet::config() const { return cfg::to_node(params_); }

std::map<std::string, double> LayersNet::step_counters() const {
  const StepCounts& c = counts_;
  return {{"vertices", c.vertices},       {"patches", c.patches},         {"body_tokens", c.body_tokens},
          {"abstract_tokens", c.abstract_tokens}, {"mesh_edges", c.mesh_edges}, {"world_edges", c.world_edges},
          {"body_edges", c.body_edges}};
}

std::shared_ptr<const zoo::Model::Derived> LayersNet::derive(const zoo::SequenceStatic& data) {
  auto cached = std::make_shared<Cached>();
  cached->topology = build_topology(data, params_.patch_size);
  if (base_ == Base::bones) cached->joints = bind_to_bones(data);
  if (base_ == Base::skin) check_skin_data(data);
  return cached;
}

zoo::StepOutput LayersNet::predict(const zoo::StepInput& in) {
  if (in.garments.empty()) return {};
  const SceneTopology& t = derived<Cached>().topology;
  const zoo::Normalization& norm = normalization();
  const at::Device dev = device();
  const at::TensorOptions f32 = at::TensorOptions().dtype(at::kFloat).device(dev);
  const std::int64_t P = t.patches(), V = t.vertices();
  const auto radius = static_cast<float>(params_.body_radius);

  // Root-relative garment state (velocities: differences of root-relative positions).
  std::vector<at::Tensor> current, prev;
  for (const zoo::GarmentState& g : in.garments) {
    current.push_back(g.current.to(at::kFloat));
    prev.push_back(g.prev.to(at::kFloat));
  }
  const at::Tensor x = at::cat(current), x_prev = at::cat(prev);
  const StepFrames frames(in, params_.heading_frame);
  const at::Tensor p_rel = frames.to_local(1, x), v_rel = p_rel - frames.to_local(0, x_prev);
  const at::Tensor state = at::cat({norm.garment_position.normalize(p_rel), norm.garment_velocity.normalize(v_rel)}, 1);
  const at::Tensor body = in.body.to(at::kFloat), body_next = in.body_next.to(at::kFloat);
  // Body vertices `ids` in the moving frames: position at t+1 and
  // displacement t -> t+1, and their normalised state.
  struct LocalBody {
    at::Tensor next, displacement;
  };
  auto local_body = [&](const at::Tensor& ids) {
    const at::Tensor next = frames.to_local(2, body_next.index_select(0, ids));
    return LocalBody{next, next - frames.to_local(1, body.index_select(0, ids))};
  };
  auto body_state = [&](const LocalBody& b) {
    return at::cat({norm.body_position.normalize(b.next), norm.body_velocity.normalize(b.displacement)}, 1);
  };

  // Patches and the step's graph: world edges between centroids, body senders.
  const at::Tensor patch_state = patch_mean(t, state);
  const at::Tensor centroid = patch_mean(t, x.detach());
  const at::Tensor eye = at::eye(P, f32.dtype(at::kBool));
  const at::Tensor world = (at::cdist(centroid, centroid) < params_.world_radius) & t.mesh_mask.logical_not() &
                           eye.logical_not();
  const BodyContacts contacts =
      find_body_contacts(body_next, centroid, x, params_.body_radius, params_.max_body_senders);
  const at::Tensor body_ids = contacts.ids.to(dev), slot_valid = contacts.slot_valid.to(dev);

  // Tokens.
  at::Tensor patches = encode_state_->forward(at::cat({patch_state, t.patch_kind}, 1));
  const std::int64_t B = body_ids.numel();
  const at::Tensor body_kind = at::tensor({0.0f, 0.0f, 1.0f}, f32).expand({B, kKinds});
  const at::Tensor body_tokens = encode_state_->forward(at::cat({body_state(local_body(body_ids)), body_kind}, 1));
  std::vector<at::Tensor> abstract = {gravity_};
  std::vector<at::Tensor> abstract_mask = {at::ones({P, 1}, f32.dtype(at::kBool))};
  if (wind_present(in)) {
    abstract.push_back(encode_wind_->forward(wind_features(in, norm, frames)));
    abstract_mask.push_back(at::ones({P, 1}, f32.dtype(at::kBool)));
  }
  if (t.attributes.size(0) > 0) {
    abstract.push_back(encode_attributes_->forward(t.attributes));
    abstract_mask.push_back(t.patch_attribute);
  }
  const at::Tensor abstract_tokens = at::cat(abstract), to_abstract = at::cat(abstract_mask, 1);

  // Heads 0..H/2-1 see E^M, the others E^W; both see themselves and the
  // abstract tokens; body senders reach the E^W heads only.
  SenderGraph graph;
  graph.dense_mask = at::stack({at::cat({t.mesh_mask | eye, to_abstract}, 1), at::cat({world | eye, to_abstract}, 1)});
  graph.body_slot = contacts.slot.to(dev);
  graph.body_mask = at::stack({at::zeros_like(slot_valid), slot_valid});
  for (const auto& block : blocks_) patches = block->forward(patches, abstract_tokens, body_tokens, graph);

  // Decoder: per vertex, its state relative to its patches, their mean
  // embedding and its nearest next-frame body vertex (zero if none is
  // within the radius).
  const at::Tensor near_ids = contacts.nearest.to(dev), near_valid = contacts.nearest_valid.to(dev).unsqueeze(1);
  const at::Tensor offset =
      frames.vectors_to_local(2, body_next.index_select(0, near_ids) - x) / std::max(radius, 1e-12f);
  const LocalBody nearest = local_body(near_ids);
  const at::Tensor near = at::cat({body_state(nearest), offset, at::ones({V, 1}, f32)}, 1);
  const at::Tensor features =
      at::cat({state - vertex_mean(t, patch_state), at::where(near_valid, near, at::zeros_like(near))}, 1);
  const at::Tensor decoded = decoder_->forward(features, patches, t);
  const at::Tensor acceleration = norm.garment_acceleration.denormalize(decoded.narrow(1, 0, 3));

  // v(t+1) = base + a, p(t+1) = p(t) + v(t+1) in the moving frame; back to
  // world. The base is v(t) (inertial) or, where it applies, the followed
  // motion: the nearest body vertex's displacement t -> t+1 ("body", where
  // one lies within the radius) or the vertex carried by the joints it is
  // bound to ("bones", "skin": within the radius, or everywhere with a
  // learned blend); a learned blend takes v + g (follow - v) there instead.
  at::Tensor base = v_rel;
  if (base_ != Base::inertial) {
    at::Tensor follow;
    if (base_ == Base::body) {
      follow = nearest.displacement;
    } else {
      if (!in.joints.defined() || !in.joints_next.defined())
        throw Error("layersnet: bases 'bones' and 'skin' need the joint transforms at t and t+1 (LAYERS-H5 body/joints)");
      const Cached& cached = derived<Cached>();
      if (base_ == Base::skin)
        std::call_once(cached.skin_bound, [&] { cached.joints = bind_to_skin(sequence(), in.body, in.joints); });
      const zoo::JointSteps steps = zoo::joint_steps(in.joints.to(at::kFloat), in.joints_next.to(at::kFloat));
      follow = frames.to_local(2, zoo::move_with_joints(steps, x, cached.joints.joint, cached.joints.weight)) - p_rel;
    }
    if (learned_blend_) follow = v_rel + at::sigmoid(decoded.narrow(1, 3, 1)) * (follow - v_rel);
    // The joints' motion is defined everywhere; a learned blend uses it so.
    const bool everywhere = learned_blend_ && base_ != Base::body;
    base = everywhere ? follow : at::where(near_valid, follow, v_rel);
  }
  const at::Tensor next = frames.to_world(2, p_rel + base + acceleration);
  zoo::StepOutput out;
  for (std::size_t k = 0; k + 1 < t.vertex_offset.size(); ++k)
    out.garments.push_back(next.narrow(0, t.vertex_offset[k], t.vertex_offset[k + 1] - t.vertex_offset[k]));

  counts_.vertices = V;
  counts_.patches = P;
  counts_.body_tokens = B;
  counts_.abstract_tokens = abstract_tokens.size(0);
  counts_.mesh_edges = t.mesh_edges;
  counts_.world_edges = world.sum().item<std::int64_t>() / 2;
  counts_.body_edges = slot_valid.sum().item<std::int64_t>();
  return out;
}

std::shared_ptr<zoo::Model> make_layersnet(const cfg::Node& params) {
  return std::make_shared<LayersNet>(read_params(params));
}

}  // namespace layers::layersnet
