// The DeePSD model: static per-garment inputs, heads, pose embedding,
// skinning, and the first-epoch priors (see deepsd_model.h).
#include "deepsd_model.h"

#include <ATen/core/grad_mode.h>

#include <array>
#include <memory>
#include <string>

#include "garment_graph.h"
#include "layers/core/error.h"
#include "layers/zoo/losses.h"
#include "layers/zoo/phase.h"
#include "layers/zoo/skinning.h"
#include "pose_features.h"

namespace layers::deepsd {
namespace {

// Min-max ranges of mass, tension, compression, shear, bending, friction,
// self_friction (the paper's sampling ranges).
constexpr std::array<float, kAttributes> kAttributeLo{0.2f, 15, 15, 15, 15, 40, 40};
constexpr std::array<float, kAttributes> kAttributeHi{0.8f, 100, 100, 100, 200, 80, 80};
constexpr double kCm2 = 1e4;  // m^2 -> cm^2

[[noreturn]] void fail(const std::string& field, const std::string& expected, const std::string& got) {
  throw Error(std::string("model '") + kDeepsd.name + "': " + field + ": expected " + expected + ", got " + got);
}

at::Tensor scaled_attributes(const at::Tensor& a) {
  const at::Tensor lo = at::tensor(std::vector<float>(kAttributeLo.begin(), kAttributeLo.end()), a.options());
  const at::Tensor hi = at::tensor(std::vector<float>(kAttributeHi.begin(), kAttributeHi.end()), a.options());
  return (a - lo) / (hi - lo);
}

}  // namespace

// Per garment of a sequence: what the heads read (rest frame) and the
// rest shape (world); per sequence: the T-pose, its root and the lazily
// made prior targets and heads made without gradients.
struct DeepsdModel::Inputs : Derived {
  struct Garment {
    GarmentGraph graph;
    at::Tensor features;    // [V,6] rest position (relative to the root) and normal, rest frame
    at::Tensor attributes;  // [A] scaled to [0,1]
    at::Tensor rest;        // [V,3] world
  };
  std::vector<Garment> garments;
  at::Tensor tpose;          // [J,3,4]
  at::Tensor rest_rotation;  // [3,3] R_root(T): rest frame -> world
  std::int64_t root = 0;

  mutable std::vector<at::Tensor> prior_targets;   // [V,J] per garment, once made
  mutable std::vector<GarmentHeads> cached_heads;  // made without gradients, at cached_version
  mutable std::int64_t cached_version = -1;
  // Made with gradients: shared by the steps of one backward pass (a
  // training window's loss steps), until that pass reaches them (a hook on
  // each head clears `graph_alive`) or a parameter changes.
  mutable std::vector<GarmentHeads> graph_heads;
  mutable std::int64_t graph_version = -1;
  mutable std::shared_ptr<bool> graph_alive = std::make_shared<bool>(false);
};

DeepsdModel::DeepsdModel(const DeepsdParams& params) : Model(kDeepsd.name), params_(params) {
  std::int64_t width = 6;
  for (std::size_t i = 0; i < params_.graph_widths.size(); ++i) {
    graph_.push_back(
        register_module("graph" + std::to_string(i), GraphLayer(GraphLayerOptions(width, params_.graph_widths[i]))));
    width = params_.graph_widths[i];
  }
  const std::int64_t descriptor = 2 * width + kAttributes;
  // DeePSD's heads name their layers "0", "1", ... in checkpoints.
  auto head = [](std::int64_t in, const std::vector<int>& hidden, std::int64_t out) {
    return zoo::Mlp(zoo::MlpOptions(in, std::vector<std::int64_t>(hidden.begin(), hidden.end()), out).layer_prefix(""));
  };
  weight_head_ = register_module("weight_head", head(descriptor, params_.weight_head, params_.joints));
  deformation_head_ =
      register_module("deformation_head", head(descriptor, params_.deformation_head, 3 * params_.basis));
  pose_head_ = register_module("pose_head",
                               head(pose_feature_size(params_.joints, params_.wind), params_.pose_head, params_.basis));
  // Start as plain skinning: no deformation until trained.
  at::NoGradGuard no_grad;
  deformation_head_->last()->weight.zero_();
  deformation_head_->last()->bias.zero_();
}

std::shared_ptr<const zoo::Model::Derived> DeepsdModel::derive(const zoo::SequenceStatic& data) {
  const std::string where = "sequence '" + data.id + "'";
  if (!data.tpose_joints.defined()) {
    throw InputError(where, "tpose_joints",
                     "the T-pose joint transforms [J,3,4] the garments were made in (LAYERS-H5 body/tpose_joints; "
                     "regenerate a dataset made before it existed)",
                     "none");
  }
  if (data.tpose_joints.size(0) != params_.joints) {
    throw InputError(where, "tpose_joints", std::to_string(params_.joints) + " joints (model.params.joints)",
                     std::to_string(data.tpose_joints.size(0)));
  }
  auto out = std::make_shared<Inputs>();
  out->tpose = data.tpose_joints;
  out->root = zoo::root_joint(data.joint_parents);
  out->rest_rotation = data.tpose_joints[out->root].slice(1, 0, 3);
  const at::Tensor origin = data.tpose_joints[out->root].select(1, 3);
  for (std::size_t k = 0; k < data.garments.size(); ++k) {
    const zoo::GarmentStatic& g = data.garments[k];
    if (g.attributes.size(0) != kAttributes) {
      throw InputError(where, "garments[" + std::to_string(k) + "] (" + g.name + ").attributes",
                       "7 attributes (mass, tension, compression, shear, bending, friction, self_friction)",
                       std::to_string(g.attributes.size(0)));
    }
    Inputs::Garment in;
    in.graph = mesh_graph(g.faces, g.rest.size(0));
    const at::Tensor normals = zoo::vertex_normals(g.rest, g.faces);
    // Row vectors: x_rest = R^T (x - o)  <=>  (x - o) R.
    in.features =
        at::cat({at::matmul(g.rest - origin, out->rest_rotation), at::matmul(normals, out->rest_rotation)}, 1);
    in.attributes = scaled_attributes(g.attributes);
    in.rest = g.rest;
    out->garments.push_back(std::move(in));
  }
  return out;
}

const DeepsdModel::Inputs& DeepsdModel::inputs() const { return derived<Inputs>(); }

GarmentHeads DeepsdModel::heads(std::size_t garment) {
  const zoo::Phase phase_garment_heads("phase:garment_heads");
  const Inputs::Garment& g = inputs().garments.at(garment);
  at::Tensor h = g.features;
  for (auto& layer : graph_) h = layer->forward(h, g.graph);
  const std::int64_t v = h.size(0);
  const at::Tensor global = std::get<0>(h.max(0)).expand({v, h.size(1)});
  const at::Tensor descriptor = at::cat({h, global, g.attributes.expand({v, kAttributes})}, 1);
  GarmentHeads out;
  out.weights = at::softmax(weight_head_->forward(descriptor), 1);
  out.basis = deformation_head_->forward(descriptor).view({v, params_.basis, 3});
  return out;
}

std::int64_t DeepsdModel::parameters_version() const {
  std::int64_t version = 0;
  for (const at::Tensor& p : parameters(true)) version += static_cast<std::int64_t>(p._version());
  return version;
}

std::vector<GarmentHeads> DeepsdModel::all_heads(bool& reused) {
  const Inputs& in = inputs();
  // The heads depend on the parameters only (no dropout or batch
  // statistics). Without gradients they are reused until a parameter
  // changes; with gradients, by the steps before the next backward pass
  // through them (the same values, one graph: the pass sums their
  // gradients as it would over separate copies).
  const std::int64_t version = parameters_version();
  if (!at::GradMode::is_enabled()) {
    reused = in.cached_version == version;
    if (reused) return in.cached_heads;
    in.cached_heads.clear();
    for (std::size_t k = 0; k < in.garments.size(); ++k) in.cached_heads.push_back(heads(k));
    in.cached_version = version;
    return in.cached_heads;
  }
  reused = *in.graph_alive && in.graph_version == version;
  if (reused) return in.graph_heads;
  in.graph_heads.clear();
  in.graph_alive = std::make_shared<bool>(true);
  const std::shared_ptr<bool> alive = in.graph_alive;
  for (std::size_t k = 0; k < in.garments.size(); ++k) {
    GarmentHeads h = heads(k);
    for (at::Tensor* t : {&h.weights, &h.basis})
      if (t->requires_grad()) t->register_hook([alive](const at::Tensor&) { *alive = false; });
    in.graph_heads.push_back(std::move(h));
  }
  in.graph_version = version;
  return in.graph_heads;
}

at::Tensor DeepsdModel::pose_embedding(const zoo::StepInput& in) {
  const zoo::Phase phase_pose("phase:pose");
  if (!in.joints_next.defined())
    fail("step input joints_next", "the joint transforms at t+1 [J,3,4] (LAYERS-H5 body/joints)", "nothing");
  const Inputs& inputs = this->inputs();
  const at::Tensor features =
      pose_features(inputs.tpose, in.joints_next, inputs.root, params_.wind, in.wind_rotation[1], in.wind_strength[1]);
  return pose_head_->forward(features);
}

zoo::StepOutput DeepsdModel::predict(const zoo::StepInput& in) {
  const Inputs& inputs = this->inputs();
  const at::Tensor coefficients = pose_embedding(in);
  const at::Tensor maps = zoo::tpose_to_frame(inputs.tpose, in.joints_next);
  last_ = LastStep{};
  last_.sequence = sequence().id;
  bool reused = false;
  last_.heads = all_heads(reused);
  const zoo::Phase phase_skinning("phase:skinning");
  zoo::StepOutput out;
  std::int64_t vertices = 0;
  for (std::size_t k = 0; k < inputs.garments.size(); ++k) {
    const GarmentHeads& h = last_.heads[k];
    const at::Tensor offsets = at::matmul(h.basis.transpose(1, 2), coefficients);  // [V,3], rest frame
    const at::Tensor shape = inputs.garments[k].rest + at::matmul(offsets, inputs.rest_rotation.transpose(0, 1));
    out.garments.push_back(zoo::skin(shape, h.weights, maps));
    last_.offsets.push_back(offsets);
    vertices += offsets.size(0);
  }
  last_.body_next = in.body_next;
  last_.maps = maps;
  last_.counters = {
      {"garment_vertices", double(vertices)}, {"joints", double(params_.joints)}, {"heads_reused", reused ? 1.0 : 0.0}};
  return out;
}

std::vector<at::Tensor> DeepsdModel::prior_targets(const Inputs& in) {
  if (!in.prior_targets.empty()) return in.prior_targets;
  const zoo::SequenceStatic& s = sequence();
  if (!s.skin_index.defined()) {
    throw InputError("sequence '" + s.id + "'", "skin_index",
                     "the body's skinning weights (LAYERS-H5 body/skin_index, body/skin_weight) for the weight prior",
                     "none");
  }
  at::NoGradGuard no_grad;
  const at::Tensor body = zoo::unskin(last_.body_next.detach(), s.skin_index, s.skin_weight, last_.maps.detach())
                              .to(at::kCPU, at::kFloat)
                              .contiguous();
  if (!at::isfinite(body).all().item<bool>())
    fail("weight prior", "a body that maps back to the T-pose (invertible blended joint rotations)", "NaN");
  const at::Tensor weights = zoo::dense_weights(s.skin_index, s.skin_weight, params_.joints);
  if (in.garments.empty()) return in.prior_targets;
  // One k-d tree over the T-pose body for every garment's rest vertices.
  std::vector<at::Tensor> rests;
  std::vector<std::int64_t> sizes;
  for (const Inputs::Garment& g : in.garments) {
    rests.push_back(g.rest);
    sizes.push_back(g.rest.size(0));
  }
  const at::Tensor rows = zoo::nearest_body_vertex(at::cat(rests), body).to(weights.device());
  for (const at::Tensor& r : rows.split_with_sizes(sizes)) in.prior_targets.push_back(weights.index_select(0, r));
  return in.prior_targets;
}

std::vector<zoo::LossTerm> DeepsdModel::auxiliary_losses(const zoo::TrainingContext& context) {
  if (context.epoch >= params_.prior_epochs) return {};
  if (last_.sequence.empty() || !prepared() || last_.sequence != sequence().id)
    fail("auxiliary_losses", "a step on the current sequence first", "none");
  std::vector<zoo::LossTerm> out;
  if (params_.weight_prior > 0) {
    const std::vector<at::Tensor> targets = prior_targets(inputs());
    std::vector<at::Tensor> errors;
    for (std::size_t k = 0; k < targets.size(); ++k)
      errors.push_back((last_.heads[k].weights - targets[k]).pow(2).sum(1));
    out.push_back({"weight_prior", params_.weight_prior * at::cat(errors).mean()});
  }
  if (params_.deformation_prior > 0) {
    std::vector<at::Tensor> sizes;
    for (const at::Tensor& d : last_.offsets) sizes.push_back(d.pow(2).sum(1));
    out.push_back({"deformation_prior", params_.deformation_prior * kCm2 * at::cat(sizes).mean()});
  }
  return out;
}

std::shared_ptr<zoo::Model> make_deepsd_model(const cfg::Node& params) {
  return std::make_shared<DeepsdModel>(read_params(params));
}

}  // namespace layers::deepsd
