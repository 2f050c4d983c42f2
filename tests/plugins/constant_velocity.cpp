// The constant-velocity test model (see constant_velocity.h).
#include "constant_velocity.h"

#include "layers/core/config.h"
#include "layers/zoo/model.h"

namespace layers::test {
namespace {

struct Params {
  double damping = 0.0;
  template <class V>
  void visit(V& v) {
    v("damping", damping, cfg::opt().range(0, 1).help("share of the velocity lost per frame"));
  }
};

class ConstantVelocity : public zoo::Model {
 public:
  explicit ConstantVelocity(const Params& p) : Model(kConstantVelocity.name) {
    damping_ = register_parameter("damping", at::scalar_tensor(p.damping, at::kFloat));
  }

  cfg::Node config() const override {
    Params p;
    p.damping = damping_.item<double>();
    return cfg::to_node(p);
  }

 protected:
  zoo::StepOutput predict(const zoo::StepInput& in) override {
    zoo::StepOutput out;
    for (const zoo::GarmentState& g : in.garments)
      out.garments.push_back(g.current + (1 - damping_) * (g.current - g.prev));
    return out;
  }

 private:
  at::Tensor damping_;
};

}  // namespace

std::shared_ptr<zoo::Model> make_constant_velocity(const cfg::Node& params) {
  return std::make_shared<ConstantVelocity>(cfg::read<Params>(params));
}

}  // namespace layers::test
