// The "skinned" reference model (see skinned_model.h): binding garment
// vertices to body vertices' skinning weights, and moving them with the
// blended joint motion from t to t+1.
#include "skinned_model.h"

#include <vector>

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/geometry/nearest.h"
#include "layers/zoo/joint_motion.h"
#include "layers/zoo/model.h"
#include "layers/zoo/model_config.h"

namespace layers::reference {
namespace {

[[noreturn]] void fail(const std::string& field, const std::string& expected, const std::string& got) {
  throw Error(std::string("model '") + kSkinnedName + "': " + field + ": expected " + expected + ", got " + got);
}

// A detached float32 CPU copy of [N,3] positions; `field` names them in
// the error when one is not finite.
geometry::Points finite_cpu_points(const at::Tensor& t, const std::string& field) {
  at::Tensor cpu = t.detach().to(at::kCPU, at::kFloat).contiguous();
  geometry::Points out = Eigen::Map<const geometry::Points>(cpu.data_ptr<float>(), cpu.size(0), 3);
  if (!out.allFinite()) fail(field, "finite positions to bind the garments to the body", "NaN or infinity");
  return out;
}

class SkinnedModel : public zoo::Model {
 public:
  SkinnedModel() : Model(kSkinnedName) {}

  cfg::Node config() const override { return cfg::to_node(zoo::NoParams{}); }

 protected:
  // Per garment: the joints [V,4] (int64) and weights [V,4] (sum 1) of the
  // body vertex each garment vertex is bound to. Filled on the first step
  // after the sequence was derived (see skinned_model.h), hence mutable.
  struct Binding : Derived {
    mutable bool bound = false;
    mutable std::vector<at::Tensor> joints;
    mutable std::vector<at::Tensor> weights;
    mutable std::int64_t max_joint = -1;
  };

  std::shared_ptr<const Derived> derive(const zoo::SequenceStatic& data) override {
    if (!data.skin_index.defined()) {
      throw InputError("sequence '" + data.id + "'", "skin_index",
                       "skinning data (LAYERS-H5 body/skin_index and body/skin_weight) for model 'skinned'",
                       "none");
    }
    return std::make_shared<Binding>();
  }

  zoo::StepOutput predict(const zoo::StepInput& in) override {
    if (!in.joints.defined() || !in.joints_next.defined()) {
      fail("step input joints / joints_next",
           "the joint transforms [J,3,4] at t and t+1 (LAYERS-H5 body/joints)",
           in.joints.defined() ? "no joints_next" : "no joints");
    }
    const Binding& binding = derived<Binding>();
    if (!binding.bound) bind(binding, in);
    const std::int64_t nj = in.joints.size(0);
    if (binding.max_joint >= nj) {
      fail("step input joints", "at least " + std::to_string(binding.max_joint + 1) +
           " joints (skin_index names joint " + std::to_string(binding.max_joint) + ")",
           std::to_string(nj));
    }

    const zoo::JointSteps steps = zoo::joint_steps(in.joints, in.joints_next);
    zoo::StepOutput out;
    for (std::size_t k = 0; k < in.garments.size(); ++k)
      out.garments.push_back(
          zoo::move_with_joints(steps, in.garments[k].current, binding.joints[k], binding.weights[k]));
    return out;
  }

 private:
  // Binds every garment vertex to the nearest body vertex at t.
  void bind(const Binding& binding, const zoo::StepInput& in) const {
    const zoo::SequenceStatic& s = sequence();
    const geometry::PointIndex body(finite_cpu_points(in.body, "step input body"));
    std::vector<at::Tensor> joints, weights;
    std::int64_t lo = 0, hi = -1;
    for (std::size_t k = 0; k < in.garments.size(); ++k) {
      const at::Tensor& current = in.garments[k].current;
      Eigen::VectorXi nearest =
          body.nearest_all(finite_cpu_points(current, "step input garments[" + std::to_string(k) + "].current"));
      at::Tensor index =
          at::from_blob(nearest.data(), {nearest.size()}, at::kInt).to(at::kLong).to(s.skin_index.device());
      at::Tensor j = s.skin_index.index_select(0, index);
      at::Tensor w = s.skin_weight.index_select(0, index);
      at::Tensor sums = w.sum(1, /*keepdim=*/true);
      if (nearest.size() > 0) {
        const double smallest = sums.min().item<double>();
        if (!(smallest > 0)) {
          throw InputError("sequence '" + s.id + "'", "skin_weight",
                           "a positive weight sum for every body vertex a garment vertex binds to",
                           "a sum of " + std::to_string(smallest));
        }
        lo = std::min(lo, j.min().item<std::int64_t>());
        hi = std::max(hi, j.max().item<std::int64_t>());
      }
      joints.push_back(j);
      weights.push_back(w / sums);
    }
    if (lo < 0) fail("sequence '" + s.id + "' skin_index", "joint indices >= 0", std::to_string(lo));
    binding.joints = std::move(joints);
    binding.weights = std::move(weights);
    binding.max_joint = hi;
    binding.bound = true;
  }
};

}  // namespace

std::shared_ptr<zoo::Model> make_skinned_model(const cfg::Node& params) {
  if (params.kind != cfg::Node::Kind::Null) cfg::read<zoo::NoParams>(params);
  return std::make_shared<SkinnedModel>();
}

}  // namespace layers::reference
