// The "skinned" reference model (see spec.h): binding garment
// vertices to body vertices' skinning weights on the first step, and
// moving them with the blended joint motion from t to t+1.
#include "spec.h"

#include <vector>

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/zoo/model.h"
#include "layers/zoo/model_config.h"
#include "layers/zoo/skinning.h"

namespace layers::reference {
namespace {

[[noreturn]] void fail(const std::string& field, const std::string& expected, const std::string& got) {
  throw Error(std::string("model '") + kSkinned.name + "': " + field + ": expected " + expected + ", got " + got);
}

// Refuses positions that are not finite; `field` names them.
void check_finite(const at::Tensor& t, const std::string& field) {
  if (!at::isfinite(t.detach()).all().item<bool>())
    fail(field, "finite positions to bind the garments to the body", "NaN or infinity");
}

class SkinnedModel : public zoo::Model {
 public:
  SkinnedModel() : Model(kSkinned.name) {}

  cfg::Node config() const override { return cfg::to_node(zoo::NoParams{}); }

 protected:
  // What derive() checked: the sequence has skinning data.
  struct Skinnable : Derived {};

  // Per garment: the joints [V,4] (int64) and weights [V,4] (sum 1) of the
  // body vertex each garment vertex is bound to (see spec.h).
  struct Binding : Derived {
    std::vector<zoo::SkinBinding> garments;
    std::int64_t max_joint = -1;
  };

  std::shared_ptr<const Derived> derive(const zoo::SequenceStatic& data) override {
    if (!data.skin_index.defined()) {
      throw InputError("sequence '" + data.id + "'", "skin_index",
                       "skinning data (LAYERS-H5 body/skin_index and body/skin_weight) for model 'skinned'", "none");
    }
    return std::make_shared<Skinnable>();
  }

  // Binds every garment vertex to the nearest body vertex at t.
  std::shared_ptr<const Derived> bind(const zoo::SequenceStatic& s, std::shared_ptr<const Derived>,
                                      const zoo::StepInput& in) override {
    check_finite(in.body, "step input body");
    auto binding = std::make_shared<Binding>();
    std::int64_t lo = 0;
    for (std::size_t k = 0; k < in.garments.size(); ++k) {
      const at::Tensor& current = in.garments[k].current;
      check_finite(current, "step input garments[" + std::to_string(k) + "].current");
      const at::Tensor rows = zoo::nearest_body_vertex(current, in.body).to(s.skin_index.device());
      if (rows.size(0) > 0) {
        const double smallest = s.skin_weight.index_select(0, rows).sum(1).min().item<double>();
        if (!(smallest > 0)) {
          throw InputError("sequence '" + s.id + "'", "skin_weight",
                           "a positive weight sum for every body vertex a garment vertex binds to",
                           "a sum of " + std::to_string(smallest));
        }
      }
      zoo::SkinBinding b = zoo::skin_of_rows(rows, s.skin_index, s.skin_weight);
      if (rows.size(0) > 0) {
        lo = std::min(lo, b.joint.min().item<std::int64_t>());
        binding->max_joint = std::max(binding->max_joint, b.joint.max().item<std::int64_t>());
      }
      binding->garments.push_back(std::move(b));
    }
    if (lo < 0) fail("sequence '" + s.id + "' skin_index", "joint indices >= 0", std::to_string(lo));
    return binding;
  }

  zoo::StepOutput predict(const zoo::StepInput& in) override {
    if (!in.joints.defined() || !in.joints_next.defined()) {
      fail("step input joints / joints_next", "the joint transforms [J,3,4] at t and t+1 (LAYERS-H5 body/joints)",
           in.joints.defined() ? "no joints_next" : "no joints");
    }
    const Binding& binding = derived<Binding>();
    const std::int64_t nj = in.joints.size(0);
    if (binding.max_joint >= nj) {
      fail("step input joints",
           "at least " + std::to_string(binding.max_joint + 1) + " joints (skin_index names joint " +
               std::to_string(binding.max_joint) + ")",
           std::to_string(nj));
    }

    const zoo::JointSteps steps = zoo::joint_steps(in.joints, in.joints_next);
    zoo::StepOutput out;
    for (std::size_t k = 0; k < in.garments.size(); ++k)
      out.garments.push_back(
          zoo::move_with_joints(steps, in.garments[k].current, binding.garments[k].joint, binding.garments[k].weight));
    return out;
  }
};

}  // namespace

std::shared_ptr<zoo::Model> make_skinned_model(const cfg::Node& params) {
  if (params.kind != cfg::Node::Kind::Null) cfg::read<zoo::NoParams>(params);
  return std::make_shared<SkinnedModel>();
}

}  // namespace layers::reference
