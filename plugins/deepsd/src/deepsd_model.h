// plugins/deepsd/src/deepsd_model.h -- the DeePSD baseline (docs/deepsd.md).
//
// Per garment, from its rest shape only (so once per sequence):
//   rest position + vertex normal (6, in the body's rest frame) -> graph
//   layers (mean over mesh neighbours, widths graph_widths) -> per-vertex
//   descriptor; its max over the vertices is the global descriptor; both,
//   with the garment's seven attributes min-max scaled, feed
//   - the blend-weight head -> softmax over the J joints: w_v [J];
//   - the deformation head -> K basis vectors per vertex: B_v [K,3].
// Per step, the pose at t+1 (and the wind, see pose_features.h) goes
// through the pose embedding to K coefficients e, the deformation is
// d_v = B_v^T e (rest frame, turned to the T-pose's world frame) and
//   p_v(t+1) = sum_j w_vj G_j(t+1) G_j(T)^-1 (rest_v + d_v)
// with G(T) = SequenceStatic::tpose_joints and G(t+1) = StepInput::
// joints_next. The garment state is ignored: like the public DeePSD code,
// the model is static (no dynamics); deepsd+ is the same model trained with
// the layer collision loss (configs/models/deepsd_plus.yaml).
//
// Auxiliary losses (first `prior_epochs` epochs): the blend weights pulled
// to the skinning weights of the body vertex nearest to each rest vertex,
// and a small prior on |d|. The T-pose body is not stored; it is the body
// at t+1 of the first step that needs it, mapped back to the T-pose by
// inverting its skinning (exact: the body is skinned with the same joints).
//
// Without gradients (rollouts, evaluation, the trainer's curriculum
// steps), the per-garment heads are computed once per sequence and reused
// until a parameter changes (the parameters' version counters): a step is
// then the pose embedding and the skinning only.
#pragma once

#include <ATen/ATen.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "graph_layer.h"
#include "layers/zoo/mlp.h"
#include "layers/zoo/model.h"
#include "params.h"
#include "spec.h"

namespace layers::deepsd {

// The garment attributes' paper ranges (zoo::GarmentStatic::attributes
// order), scaled to [0,1].
inline constexpr int kAttributes = 7;

// The static outputs for one garment.
struct GarmentHeads {
  at::Tensor weights;  // [V,J] blend weights, rows sum to 1
  at::Tensor basis;    // [V,K,3] deformation basis, body rest frame
};

class DeepsdModel : public zoo::Model {
 public:
  explicit DeepsdModel(const DeepsdParams& params);

  cfg::Node config() const override { return cfg::to_node(params_); }
  const DeepsdParams& params() const { return params_; }
  std::vector<zoo::LossTerm> auxiliary_losses(const zoo::TrainingContext& context) override;
  // garment_vertices, joints, and heads_reused (1 when the last step took
  // the heads from the cache, see above).
  std::map<std::string, double> step_counters() const override { return last_.counters; }

  // The heads of garment k of the prepared sequence (with gradients).
  GarmentHeads heads(std::size_t garment);
  // The pose embedding (K coefficients) of a step input.
  at::Tensor pose_embedding(const zoo::StepInput& in);

  zoo::MlpImpl& weight_head() { return *weight_head_; }
  zoo::MlpImpl& deformation_head() { return *deformation_head_; }

 protected:
  std::shared_ptr<const Derived> derive(const zoo::SequenceStatic& data) override;
  zoo::StepOutput predict(const zoo::StepInput& in) override;

 private:
  struct Inputs;
  const Inputs& inputs() const;
  std::vector<GarmentHeads> all_heads(bool& reused);
  std::int64_t parameters_version() const;
  std::vector<at::Tensor> prior_targets(const Inputs& inputs);

  DeepsdParams params_;
  std::vector<GraphLayer> graph_;
  zoo::Mlp weight_head_{nullptr}, deformation_head_{nullptr}, pose_head_{nullptr};

  // What the last step produced, for auxiliary_losses().
  struct LastStep {
    std::string sequence;  // id of the sequence it was on
    std::vector<GarmentHeads> heads;
    std::vector<at::Tensor> offsets;  // [V,3] d, rest frame
    at::Tensor body_next, maps;       // body at t+1, T-pose -> t+1 joint maps
    std::map<std::string, double> counters;
  } last_;
};

}  // namespace layers::deepsd
