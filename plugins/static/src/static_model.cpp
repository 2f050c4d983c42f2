// The "static" reference model (see spec.h).
#include "spec.h"

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/zoo/model.h"
#include "layers/zoo/model_config.h"
#include "layers/zoo/rotations.h"

namespace layers::reference {
namespace {

class StaticModel : public zoo::Model {
 public:
  StaticModel() : Model(kStatic.name) {}

  cfg::Node config() const override { return cfg::to_node(zoo::NoParams{}); }

 protected:
  zoo::StepOutput predict(const zoo::StepInput& in) override {
    // Rows t and t+1 of the [t-1, t, t+1] root data.
    at::Tensor rot = in.root_rot.slice(0, 1, 3);
    at::Tensor lengths = rot.norm(2, {1});
    if (!(lengths.min().item<double>() > 1e-6 && at::isfinite(rot).all().item<bool>()))
      throw Error(
          "model 'static': step input root_rot: expected non-zero, finite quaternions (w,x,y,z) at t and t+1, "
          "got lengths " +
          std::to_string(lengths[0].item<double>()) + " and " + std::to_string(lengths[1].item<double>()));
    at::Tensor r = zoo::rotation_matrices(rot);
    zoo::StepOutput out;
    for (const zoo::GarmentState& g : in.garments) {
      const auto type = g.current.scalar_type();
      at::Tensor motion = at::matmul(r[1], r[0].transpose(0, 1)).to(type);  // R(t+1) R(t)^T
      at::Tensor from = in.root[1].to(type), to = in.root[2].to(type);
      out.garments.push_back(at::matmul(g.current - from, motion.transpose(0, 1)) + to);
    }
    return out;
  }
};

}  // namespace

std::shared_ptr<zoo::Model> make_static_model(const cfg::Node& params) {
  if (params.kind != cfg::Node::Kind::Null) cfg::read<zoo::NoParams>(params);
  return std::make_shared<StaticModel>();
}

}  // namespace layers::reference
