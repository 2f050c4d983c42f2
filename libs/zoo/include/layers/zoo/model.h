// layers/zoo/model.h -- the interface every garment model implements.
//
// A model is a torch::nn::Module. Per sequence it gets the static data once
// (prepare: topology, UVs, panels, attributes), may derive and cache what
// it needs from it (patches, graphs, descriptors), and then predicts frame
// t+1 of every garment from the state at t and t-1 and the body and wind at
// t and t+1 (step). Positions are metres in world space, y up, one frame
// per step (docs/format.md). The trainer adds loss terms on top of
// step(); models may run on CPU or CUDA (prepare() moves the static data to
// the model's device).
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <ATen/ATen.h>
#include <torch/nn/module.h>

#include "layers/core/config_node.h"
#include "layers/zoo/normalization.h"

namespace layers::zoo {

// One garment's static data (LAYERS-H5 garments/<k>/). Index tensors may be
// any integer type and float tensors any floating type; prepare() stores
// them as int64 and float32.
struct GarmentStatic {
  std::string name;        // e.g. "jacket"
  std::string type;        // jacket, jacket_hood, dress, dress_belt, jumpsuit, tshirt, pants, skirt
  std::int64_t layer = 0;  // 0 = inner, 1 = outer
  at::Tensor faces;        // [F,3] vertex indices
  at::Tensor rest;         // [V,3] rest shape
  at::Tensor uv;           // [U,2]
  at::Tensor uv_faces;     // [F,3] indices into uv
  at::Tensor panel;        // [F] sewing-pattern panel of each face
  at::Tensor attributes;   // [A] mass, tension, compression, shear, bending, friction, self_friction
};

// A sequence's static data. `id` must identify it uniquely (e.g. dataset
// name + sequence id): it is the key of the per-sequence cache.
struct SequenceStatic {
  std::string id;
  at::Tensor body_faces;  // [Fb,3]
  std::vector<GarmentStatic> garments;
  // Skinning data for skeleton-driven models; undefined when absent.
  at::Tensor joint_parents;  // [J], -1 for the root
  at::Tensor skin_index;     // [Vb,4] joint indices
  at::Tensor skin_weight;    // [Vb,4]
  // Joint transforms [R|p] of the T-pose the garments' rest shapes were
  // made in ([J,3,4], same convention as StepInput::joints): a skinning
  // model maps a rest point x to frame t with
  //   G_j(t) G_j(T)^-1 x  =  R_j(t) R_j(T)^T (x - p_j(T)) + p_j(t).
  // Undefined when the data has none.
  at::Tensor tpose_joints;
};

// Garment positions at t-1 and t, each [V,3].
struct GarmentState {
  at::Tensor prev;
  at::Tensor current;
};

// Everything a step sees besides the static data.
struct StepInput {
  std::vector<GarmentState> garments;  // in SequenceStatic::garments order
  at::Tensor body;                     // [Vb,3] body vertices at t
  at::Tensor body_next;                // [Vb,3] body vertices at t+1
  at::Tensor root;                     // [3,3] pelvis translation at t-1, t, t+1
  at::Tensor root_rot;                 // [3,4] pelvis orientation (w,x,y,z) at t-1, t, t+1
  at::Tensor wind_rotation;            // [2,4] wind rotation (w,x,y,z) at t, t+1
  at::Tensor wind_strength;            // [2] wind strength (0..400) at t, t+1
  // Joint transforms [R|p] at t and t+1 ([J,3,4], LAYERS-H5 body/joints:
  // a point x of the body's rest pose moves to R (x - rest_joint) + p);
  // undefined when absent. A point moves from t to t+1 with joint j as
  // R(t+1) R(t)^T (x - p(t)) + p(t+1).
  at::Tensor joints;
  at::Tensor joints_next;
};

// Predicted garment positions at t+1, each [V,3], in garment order.
struct StepOutput {
  std::vector<at::Tensor> garments;
};

// What the trainer tells a model when it asks for auxiliary losses.
struct TrainingContext {
  int epoch = 0;          // 0-based
  std::int64_t step = 0;  // optimiser steps so far
};

// A named scalar loss term.
struct LossTerm {
  std::string name;
  at::Tensor value;  // scalar, differentiable
};

struct ModelInfo {
  std::string name;
  std::int64_t parameters = 0;  // all parameter elements
  std::int64_t trainable = 0;   // those that require grad
};

class Model : public torch::nn::Module {
 public:
  // `name` is the registered model name (also the module name).
  explicit Model(const std::string& name);
  ~Model() override;

  ModelInfo info() const;

  // The model's resolved parameters, defaults included (what a run prints
  // and saves next to its checkpoints).
  virtual cfg::Node config() const = 0;

  // Makes `data` the current sequence. Validates it (layers::InputError
  // naming the sequence and field), converts and moves it to the model's
  // device and, unless cached for this id and device, calls derive().
  void prepare(const SequenceStatic& data);
  bool prepared() const { return current_ != nullptr; }
  // The current sequence, as converted by prepare().
  const SequenceStatic& sequence() const;

  // Predicts t+1. Checks the input against the prepared sequence and the
  // output of predict() (layers::Error naming the field and shapes); after
  // moving the model to another device, prepare() again first.
  StepOutput step(const StepInput& input);

  // The training split's statistics (stats.h5) the model normalises with;
  // identity until set. The trainer sets them before training and saves
  // them with the checkpoint; the evaluator restores them.
  void set_normalization(const Normalization& norm);
  // On the model's device (moved lazily when the model moved).
  const Normalization& normalization() const;

  // Loss terms specific to this model, computed after its last step() on
  // the current sequence and added by the trainer to the shared ones
  // (layers/zoo/losses.h) with the weights the model chose (e.g. DeePSD's
  // first-epoch skinning-weight prior). Default: none.
  virtual std::vector<LossTerm> auxiliary_losses(const TrainingContext& context);

  // What the last step() used, for benchmarks and reports: counts of the
  // particles or tokens the model actually processed (e.g. "patches",
  // "body_tokens"). Default: none.
  virtual std::map<std::string, double> step_counters() const { return {}; }

  // How many sequences' derived data stay cached (least recently used
  // first out); default 64, at least 1.
  void set_cache_capacity(std::size_t capacity);
  std::size_t cached_sequences() const { return cache_.size(); }

 protected:
  // Base of what a model derives from static data; derive into a subclass.
  struct Derived {
    virtual ~Derived() = default;
  };
  // Called once per sequence id and device; the default derives nothing.
  virtual std::shared_ptr<const Derived> derive(const SequenceStatic& data);
  // Called by step() once per derived sequence, on its first step (input
  // already checked), for what needs a body frame (e.g. garments bound to
  // the skin): the data it returns replaces derive()'s for this sequence
  // and stays immutable afterwards. The default keeps `derived`.
  virtual std::shared_ptr<const Derived> bind(const SequenceStatic& data, std::shared_ptr<const Derived> derived,
                                              const StepInput& first);
  // The current sequence's derived data, as the subclass T made it.
  template <class T>
  const T& derived() const {
    return dynamic_cast<const T&>(*current_derived());
  }

  // The prediction itself; input already validated.
  virtual StepOutput predict(const StepInput& input) = 0;

  // Device of the first parameter or buffer (CPU if none).
  at::Device device() const;

 private:
  struct Prepared {
    std::string key;  // id@device
    at::Device device;
    SequenceStatic data;
    std::shared_ptr<const Derived> derived;
    bool bound = false;  // bind() ran on this sequence's first step
  };
  const Derived* current_derived() const;

  mutable Normalization norm_ = Normalization::identity();
  std::list<Prepared> cache_;  // most recently used first
  Prepared* current_ = nullptr;
  std::size_t capacity_ = 64;
};

}  // namespace layers::zoo
