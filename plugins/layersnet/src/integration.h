// plugins/layersnet/src/integration.h -- what LayersNet's predicted
// acceleration a is added to (Params::base), one strategy per base:
// v(t+1) = base + a in the moving frame of t+1. "inertial" (the paper)
// follows nothing and keeps v; "body" follows the displacement t -> t+1 of
// each vertex's nearest body vertex; "bones" and "skin" follow the vertex
// carried by the joints it is bound to (joint_binding.h). Where the
// followed motion applies, and how a learned gate blends it with v, is
// LayersNet::integrate's (layersnet.cpp).
#pragma once

#include <memory>

#include <ATen/ATen.h>

#include "frame.h"
#include "joint_binding.h"
#include "layers/zoo/model.h"
#include "params.h"

namespace layers::layersnet {

// What a base may follow, all in the moving frames of StepFrames.
struct FollowInputs {
  const zoo::StepInput& in;
  const StepFrames& frames;
  const at::Tensor& x;                     // [V,3] garment vertices at t, world
  const at::Tensor& p_rel;                 // [V,3] x in the frame of t
  const at::Tensor& nearest_displacement;  // [V,3] nearest body vertex's displacement t -> t+1
  const JointBinding& joints;              // bound joints ("bones", "skin"); empty otherwise
};

class IntegrationBase {
 public:
  virtual ~IntegrationBase() = default;
  // The followed velocity [V,3] in the frame of t+1, or an undefined
  // tensor when the base follows nothing (p + v).
  virtual at::Tensor follow(const FollowInputs& f) const = 0;
  // Whether the followed motion is defined everywhere (joints), so a
  // learned blend applies it to every vertex, not only near the body.
  virtual bool defined_everywhere() const = 0;
};

std::unique_ptr<IntegrationBase> make_integration_base(Base base);

}  // namespace layers::layersnet
