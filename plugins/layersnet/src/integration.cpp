// LayersNet's integration bases (see integration.h).
#include "integration.h"

#include "layers/core/error.h"
#include "layers/zoo/skinning.h"

namespace layers::layersnet {
namespace {

class Inertial : public IntegrationBase {
 public:
  at::Tensor follow(const FollowInputs&) const override { return {}; }
  bool defined_everywhere() const override { return false; }
};

class NearestBody : public IntegrationBase {
 public:
  at::Tensor follow(const FollowInputs& f) const override { return f.nearest_displacement; }
  bool defined_everywhere() const override { return false; }
};

// "bones" and "skin": only how the joints were bound differs.
class BoundJoints : public IntegrationBase {
 public:
  at::Tensor follow(const FollowInputs& f) const override {
    if (!f.in.joints.defined() || !f.in.joints_next.defined())
      throw Error("layersnet: bases 'bones' and 'skin' need the joint transforms at t and t+1 (LAYERS-H5 body/joints)");
    const zoo::JointSteps steps = zoo::joint_steps(f.in.joints.to(at::kFloat), f.in.joints_next.to(at::kFloat));
    return f.frames.to_local(2, zoo::move_with_joints(steps, f.x, f.joints.joint, f.joints.weight)) - f.p_rel;
  }
  bool defined_everywhere() const override { return true; }
};

}  // namespace

std::unique_ptr<IntegrationBase> make_integration_base(Base base) {
  switch (base) {
    case Base::inertial:
      return std::make_unique<Inertial>();
    case Base::body:
      return std::make_unique<NearestBody>();
    case Base::bones:
    case Base::skin:
      return std::make_unique<BoundJoints>();
  }
  throw Error("layersnet: unknown integration base");
}

}  // namespace layers::layersnet
