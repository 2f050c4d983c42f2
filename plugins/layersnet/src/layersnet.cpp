// The LayersNet model: a step in three stages -- encode (the step's graph
// and tokens), process (the TIE blocks), integrate (decoder, acceleration,
// integration base) -- see layersnet.h and docs/layersnet.md.
#include "layersnet.h"

#include <algorithm>

#include "body_contacts.h"
#include "decoder.h"
#include "frame.h"
#include "integration.h"
#include "joint_binding.h"
#include "layers/core/error.h"
#include "layers/zoo/phase.h"
#include "layers/zoo/skinning.h"
#include "tokens.h"
#include "topology.h"

namespace layers::layersnet {
namespace {

constexpr std::int64_t kState = 6;      // normalised position, velocity
constexpr std::int64_t kKinds = 3;      // inner garment, outer garment, body
constexpr std::int64_t kNearBody = 10;  // body state, offset / radius, present

// Body vertices in the moving frames: position at t+1 and displacement
// t -> t+1.
struct LocalBody {
  at::Tensor next, displacement;
};

}  // namespace

struct LayersNet::Cached : Derived {
  SceneTopology topology;
  // Bases "bones" (bound at derive) and "skin" (bound by bind() on the
  // sequence's first step: it needs a body frame).
  JointBinding joints;
};

LayersNet::LayersNet(const Params& params)
    : Model(kLayersNet.name), params_(params), base_(params.base), learned_blend_(params.blend == Blend::learned) {
  const std::int64_t d = params.width;
  encode_state_ = register_module("encode_state", zoo::Mlp(zoo::MlpOptions(kState + kKinds, {d}, d)));
  encode_attributes_ = register_module("encode_attributes", zoo::Mlp(zoo::MlpOptions(kAttributes, {d}, d)));
  encode_wind_ = register_module("encode_wind", zoo::Mlp(zoo::MlpOptions(kWindFeatures, {d}, d)));
  decoder_ = register_module("decoder", Decoder(DecoderOptions(kState + kNearBody, d).outputs(learned_blend_ ? 4 : 3)));
  gravity_ = register_parameter("gravity", at::randn({1, d}) * 0.1);
  integration_ = make_integration_base(params.base);
  for (std::int64_t b = 0; b < params.blocks; ++b)
    blocks_.push_back(register_module("block" + std::to_string(b), TieBlock(TieBlockOptions(d, params.heads))));
}

LayersNet::~LayersNet() = default;

cfg::Node LayersNet::config() const { return cfg::to_node(params_); }

std::map<std::string, double> LayersNet::step_counters() const {
  const StepCounts& c = counts_;
  return {{"vertices", c.vertices},       {"patches", c.patches},
          {"body_tokens", c.body_tokens}, {"abstract_tokens", c.abstract_tokens},
          {"mesh_edges", c.mesh_edges},   {"world_edges", c.world_edges},
          {"body_edges", c.body_edges}};
}

std::shared_ptr<const zoo::Model::Derived> LayersNet::derive(const zoo::SequenceStatic& data) {
  auto cached = std::make_shared<Cached>();
  cached->topology = build_topology(data, params_.patch_size);
  if (base_ == Base::bones) cached->joints = bind_to_bones(data);
  if (base_ == Base::skin) check_skin_data(data);
  return cached;
}

std::shared_ptr<const zoo::Model::Derived> LayersNet::bind(const zoo::SequenceStatic& data,
                                                           std::shared_ptr<const Derived> derived,
                                                           const zoo::StepInput& first) {
  if (base_ != Base::skin || first.garments.empty()) return derived;
  if (!first.joints.defined())
    throw Error("layersnet: base 'skin' needs the joint transforms at t (LAYERS-H5 body/joints)");
  auto bound = std::make_shared<Cached>(dynamic_cast<const Cached&>(*derived));
  bound->joints = bind_to_skin(data, first.body, first.joints);
  return bound;
}

// What every stage of a step reads: the sequence's topology, the moving
// frames and the garments' root-relative state.
struct LayersNet::StepContext {
  const SceneTopology& t;
  const zoo::Normalization& norm;
  at::TensorOptions f32;
  StepFrames frames;
  at::Tensor x;          // [V,3] garment vertices at t, world
  at::Tensor p_rel;      // [V,3] x in the frame of t
  at::Tensor v_rel;      // [V,3] velocity: p_rel minus x(t-1) in the frame of t-1
  at::Tensor state;      // [V,6] normalised p_rel, v_rel
  at::Tensor body;       // [Vb,3] body at t
  at::Tensor body_next;  // [Vb,3] body at t+1

  // Body vertices `ids` [N] in the moving frames.
  LocalBody local_body(const at::Tensor& ids) const {
    const at::Tensor next = frames.to_local(2, body_next.index_select(0, ids));
    return LocalBody{next, next - frames.to_local(1, body.index_select(0, ids))};
  }
  // Their normalised state [N,6].
  at::Tensor body_state(const LocalBody& b) const {
    return at::cat({norm.body_position.normalize(b.next), norm.body_velocity.normalize(b.displacement)}, 1);
  }
};

// The step's tokens and sender graph, then the processed patch tokens.
struct LayersNet::Encoded {
  at::Tensor patch_state;      // [P,6] patch means of the vertex state
  at::Tensor patches;          // [P,d] patch tokens
  at::Tensor body_tokens;      // [B,d]
  at::Tensor abstract_tokens;  // [A,d] gravity, wind, attributes
  at::Tensor world;            // [P,P] bool world edges
  BodyContacts contacts;       // body senders and each vertex's nearest body vertex (CPU)
  SenderGraph graph;
};

LayersNet::StepContext LayersNet::context(const zoo::StepInput& in) const {
  const zoo::Phase phase_context("phase:context");
  const SceneTopology& t = derived<Cached>().topology;
  const at::TensorOptions f32 = at::TensorOptions().dtype(at::kFloat).device(device());
  // Root-relative garment state (velocities: differences of root-relative positions).
  std::vector<at::Tensor> current, prev;
  for (const zoo::GarmentState& g : in.garments) {
    current.push_back(g.current.to(at::kFloat));
    prev.push_back(g.prev.to(at::kFloat));
  }
  StepContext c{t, normalization(), f32, StepFrames(in, params_.heading_frame), at::cat(current), {}, {}, {}, {}, {}};
  const at::Tensor x_prev = at::cat(prev);
  c.p_rel = c.frames.to_local(1, c.x);
  c.v_rel = c.p_rel - c.frames.to_local(0, x_prev);
  c.state = at::cat({c.norm.garment_position.normalize(c.p_rel), c.norm.garment_velocity.normalize(c.v_rel)}, 1);
  c.body = in.body.to(at::kFloat);
  c.body_next = in.body_next.to(at::kFloat);
  return c;
}

LayersNet::Encoded LayersNet::encode(const StepContext& c, const zoo::StepInput& in) {
  const zoo::Phase phase_graph("phase:graph");
  const SceneTopology& t = c.t;
  const at::Device dev = c.f32.device();
  const std::int64_t P = t.patches();
  Encoded e;
  // Patches and the step's graph: world edges between centroids, body senders.
  e.patch_state = patch_mean(t, c.state);
  const at::Tensor centroid = patch_mean(t, c.x.detach());
  const at::Tensor eye = at::eye(P, c.f32.dtype(at::kBool));
  e.world = (at::cdist(centroid, centroid) < params_.world_radius) & t.mesh_mask.logical_not() & eye.logical_not();
  {
    const zoo::Phase phase_body_search("phase:body_search");
    e.contacts = find_body_contacts(c.body_next, centroid, c.x, params_.body_radius, params_.max_body_senders);
  }
  const at::Tensor body_ids = e.contacts.ids.to(dev), slot_valid = e.contacts.slot_valid.to(dev);

  // Tokens.
  const zoo::Phase phase_tokens("phase:tokens");
  e.patches = encode_state_->forward(at::cat({e.patch_state, t.patch_kind}, 1));
  const std::int64_t B = body_ids.numel();
  const at::Tensor body_kind = at::tensor({0.0f, 0.0f, 1.0f}, c.f32).expand({B, kKinds});
  e.body_tokens = encode_state_->forward(at::cat({c.body_state(c.local_body(body_ids)), body_kind}, 1));
  std::vector<at::Tensor> abstract = {gravity_};
  std::vector<at::Tensor> abstract_mask = {at::ones({P, 1}, c.f32.dtype(at::kBool))};
  if (wind_present(in)) {
    abstract.push_back(encode_wind_->forward(wind_features(in, c.norm, c.frames)));
    abstract_mask.push_back(at::ones({P, 1}, c.f32.dtype(at::kBool)));
  }
  if (t.attributes.size(0) > 0) {
    abstract.push_back(encode_attributes_->forward(t.attributes));
    abstract_mask.push_back(t.patch_attribute);
  }
  e.abstract_tokens = at::cat(abstract);
  const at::Tensor to_abstract = at::cat(abstract_mask, 1);

  // Heads 0..H/2-1 see E^M, the others E^W; both see themselves and the
  // abstract tokens; body senders reach the E^W heads only.
  e.graph.dense_mask =
      at::stack({at::cat({t.mesh_mask | eye, to_abstract}, 1), at::cat({e.world | eye, to_abstract}, 1)});
  e.graph.body_slot = e.contacts.slot.to(dev);
  e.graph.body_mask = at::stack({at::zeros_like(slot_valid), slot_valid});
  return e;
}

void LayersNet::process(Encoded& e) {
  for (auto& block : blocks_) e.patches = block->forward(e.patches, e.abstract_tokens, e.body_tokens, e.graph);
}

at::Tensor LayersNet::integrate(const StepContext& c, const Encoded& e, const zoo::StepInput& in) {
  const zoo::Phase phase_decoder("phase:decoder");
  const SceneTopology& t = c.t;
  const at::Device dev = c.f32.device();
  const auto radius = static_cast<float>(params_.body_radius);
  // Decoder: per vertex, its state relative to its patches, their mean
  // embedding and its nearest next-frame body vertex (zero if none is
  // within the radius).
  const at::Tensor near_ids = e.contacts.nearest.to(dev), near_valid = e.contacts.nearest_valid.to(dev).unsqueeze(1);
  const at::Tensor offset =
      c.frames.vectors_to_local(2, c.body_next.index_select(0, near_ids) - c.x) / std::max(radius, 1e-12f);
  const LocalBody nearest = c.local_body(near_ids);
  const at::Tensor near = at::cat({c.body_state(nearest), offset, at::ones({t.vertices(), 1}, c.f32)}, 1);
  const at::Tensor features =
      at::cat({c.state - vertex_mean(t, e.patch_state), at::where(near_valid, near, at::zeros_like(near))}, 1);
  const at::Tensor decoded = decoder_->forward(features, e.patches, t);
  const at::Tensor acceleration = c.norm.garment_acceleration.denormalize(decoded.narrow(1, 0, 3));

  // v(t+1) = base + a, p(t+1) = p(t) + v(t+1) in the moving frame; back to
  // world. The base is v(t), or where it applies the followed motion
  // (integration.h): near the body (within the radius), or everywhere for
  // joints with a learned blend, which takes v + g (follow - v) instead.
  at::Tensor base = c.v_rel;
  at::Tensor follow =
      integration_->follow({in, c.frames, c.x, c.p_rel, nearest.displacement, derived<Cached>().joints});
  if (follow.defined()) {
    if (learned_blend_) follow = c.v_rel + at::sigmoid(decoded.narrow(1, 3, 1)) * (follow - c.v_rel);
    const bool everywhere = learned_blend_ && integration_->defined_everywhere();
    base = everywhere ? follow : at::where(near_valid, follow, c.v_rel);
  }
  return c.frames.to_world(2, c.p_rel + base + acceleration);
}

zoo::StepOutput LayersNet::predict(const zoo::StepInput& in) {
  if (in.garments.empty()) return {};
  const StepContext c = context(in);
  Encoded e = encode(c, in);
  process(e);
  const at::Tensor next = integrate(c, e, in);
  const SceneTopology& t = c.t;
  zoo::StepOutput out;
  for (std::size_t k = 0; k + 1 < t.vertex_offset.size(); ++k)
    out.garments.push_back(next.narrow(0, t.vertex_offset[k], t.vertex_offset[k + 1] - t.vertex_offset[k]));

  counts_.vertices = t.vertices();
  counts_.patches = t.patches();
  counts_.body_tokens = e.contacts.ids.numel();
  counts_.abstract_tokens = e.abstract_tokens.size(0);
  counts_.mesh_edges = t.mesh_edges;
  counts_.world_edges = e.world.sum().item<std::int64_t>() / 2;
  counts_.body_edges = e.graph.body_mask.select(0, 1).sum().item<std::int64_t>();
  return out;
}

std::shared_ptr<zoo::Model> make_layersnet(const cfg::Node& params) {
  return std::make_shared<LayersNet>(read_params(params));
}

}  // namespace layers::layersnet
