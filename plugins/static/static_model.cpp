// The "static" reference model (see static_model.h).
#include "static_model.h"

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/zoo/model.h"
#include "layers/zoo/model_config.h"

namespace layers::reference {
namespace {

// Rotation matrices [N,3,3] of quaternions [N,4] (w,x,y,z; normalised
// here, so any non-zero length will do).
at::Tensor rotation_matrices(const at::Tensor& quaternions) {
  at::Tensor q = quaternions / quaternions.norm(2, {1}, /*keepdim=*/true);
  at::Tensor w = q.select(1, 0), x = q.select(1, 1), y = q.select(1, 2), z = q.select(1, 3);
  at::Tensor rows = at::stack({1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
                               2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                               2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)},
                              1);
  return rows.view({-1, 3, 3});
}

class StaticModel : public zoo::Model {
 public:
  StaticModel() : Model(kStaticName) {}

  cfg::Node config() const override { return cfg::to_node(zoo::NoParams{}); }

 protected:
  zoo::StepOutput predict(const zoo::StepInput& in) override {
    // Rows t and t+1 of the [t-1, t, t+1] root data.
    at::Tensor rot = in.root_rot.slice(0, 1, 3);
    at::Tensor lengths = rot.norm(2, {1});
    if (!(lengths.min().item<double>() > 1e-6 && at::isfinite(rot).all().item<bool>()))
      throw Error("model 'static': step input root_rot: expected non-zero, finite quaternions (w,x,y,z) at t and t+1, "
                  "got lengths " + std::to_string(lengths[0].item<double>()) + " and " +
                  std::to_string(lengths[1].item<double>()));
    at::Tensor r = rotation_matrices(rot);
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
