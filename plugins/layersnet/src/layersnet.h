// plugins/layersnet/src/layersnet.h -- the LayersNet model (the paper and its
// public code, docs/layersnet.md): garments as UV patches, body vertices
// near the garment and abstract tokens (gravity, wind, attributes) as
// senders, a TIE-attention processor with mesh-edge and world-edge heads,
// a patch decoder back to vertices predicting accelerations.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "decoder.h"
#include "integration.h"
#include "layers/zoo/mlp.h"
#include "layers/zoo/model.h"
#include "params.h"
#include "spec.h"
#include "tie_block.h"

namespace layers::layersnet {

// What the last step used (cost follows these).
struct StepCounts {
  std::int64_t vertices = 0;  // garment vertices, all garments
  std::int64_t patches = 0;
  std::int64_t body_tokens = 0;      // distinct body vertices encoded
  std::int64_t abstract_tokens = 0;  // gravity + wind (if blowing) + attribute tokens
  std::int64_t mesh_edges = 0;       // undirected E^M
  std::int64_t world_edges = 0;      // undirected E^W
  std::int64_t body_edges = 0;       // patch <- body sender pairs
};

class LayersNet : public zoo::Model {
 public:
  explicit LayersNet(const Params& params);
  ~LayersNet() override;

  cfg::Node config() const override;
  const Params& params() const { return params_; }
  const StepCounts& last_counts() const { return counts_; }
  // last_counts() by name (vertices, patches, body_tokens, ...).
  std::map<std::string, double> step_counters() const override;

 protected:
  std::shared_ptr<const Derived> derive(const zoo::SequenceStatic& data) override;
  std::shared_ptr<const Derived> bind(const zoo::SequenceStatic& data, std::shared_ptr<const Derived> derived,
                                      const zoo::StepInput& first) override;
  zoo::StepOutput predict(const zoo::StepInput& input) override;

 private:
  struct Cached;
  struct StepContext;  // the topology, moving frames and garment state of one step
  struct Encoded;      // its tokens and sender graph

  // predict() in three stages: the step's frames and state; its graph and
  // tokens; the TIE blocks over the patch tokens; decoding and integrating
  // to the positions at t+1 [V,3] (world, all garments).
  StepContext context(const zoo::StepInput& in) const;
  Encoded encode(const StepContext& c, const zoo::StepInput& in);
  void process(Encoded& e);
  at::Tensor integrate(const StepContext& c, const Encoded& e, const zoo::StepInput& in);

  Params params_;
  Base base_;
  bool learned_blend_;
  StepCounts counts_;
  zoo::Mlp encode_state_{nullptr}, encode_attributes_{nullptr}, encode_wind_{nullptr};
  Decoder decoder_{nullptr};
  at::Tensor gravity_;  // [1,width] learned token
  std::vector<TieBlock> blocks_;
  std::unique_ptr<IntegrationBase> integration_;  // by params_.base
};

}  // namespace layers::layersnet
