// DeePSD overfits one short synthetic sequence: garments skinned with
// smooth per-vertex weights plus a pose-dependent bulge, 8 frames of a
// 4-joint skeleton (deepsd_fixture.h). Adam on the plain position MSE over
// all frames must bring the MSE down by 10x or more within 150 steps.
#include <gtest/gtest.h>

#include <torch/optim/adam.h>

#include "deepsd_fixture.h"
#include "deepsd_model.h"
#include "layers/train/compute_threads.h"

namespace layers::deepsd {
namespace {

using namespace testing;

struct Frame {
  zoo::StepInput input;
  std::vector<at::Tensor> truth;  // per garment [V,3]
};

// Ground truth: LBS with the body's height weights of the rest vertex, of
// the rest shape pushed outwards by 2 cm x sin(phase) (a pose-space
// deformation the model can learn from the joint rotations).
std::vector<Frame> sequence(const Scene& scene, int frames) {
  std::vector<Frame> out;
  for (int f = 0; f < frames; ++f) {
    const double phase = 0.25 * f;
    const Skeleton pose = posed(phase);
    Frame frame{scene.input(pose), {}};
    for (const Grid& g : scene.garments) {
      std::vector<Eigen::Vector3d> p;
      for (const auto& x : g.vertices) {
        const Eigen::Vector3d centre = scene.t[0].p + Eigen::Vector3d(0, x.y() - scene.t[0].p.y(), 0);
        const Eigen::Vector3d bulge = 0.02 * std::sin(phase) * (x - centre).normalized();
        p.push_back(lbs(pose, scene.t, height_weights(x), x + bulge));
      }
      frame.truth.push_back(points_tensor(p));
    }
    out.push_back(std::move(frame));
  }
  return out;
}

double position_mse(DeepsdModel& model, const std::vector<Frame>& frames, at::Tensor* loss = nullptr) {
  at::Tensor total = at::zeros({});
  for (const Frame& f : frames) {
    const zoo::StepOutput out = model.step(f.input);
    for (std::size_t k = 0; k < out.garments.size(); ++k)
      total = total + (out.garments[k] - f.truth[k]).pow(2).sum(1).mean();
  }
  total = total / static_cast<double>(frames.size() * 2);
  if (loss) *loss = total;
  return total.item<double>();
}

TEST(DeepsdOverfit, AdamDrivesThePositionMseDownTenfold) {
  torch::manual_seed(3);
  train::set_compute_threads(1);  // tiny tensors: threads (torch and OpenBLAS) only add overhead
  const Scene scene;
  const std::vector<Frame> frames = sequence(scene, 8);
  const DeepsdParams p = scene_params(16);
  DeepsdModel model(p);
  model.prepare(scene.statics());
  torch::optim::Adam adam(model.parameters(), torch::optim::AdamOptions(3e-3));

  const double initial = position_mse(model, frames);
  double last = initial;
  for (int step = 0; step < 150; ++step) {
    adam.zero_grad();
    at::Tensor loss;
    last = position_mse(model, frames, &loss);
    loss.backward();
    adam.step();
  }
  last = position_mse(model, frames);
  RecordProperty("initial_mse", std::to_string(initial));
  RecordProperty("final_mse", std::to_string(last));
  EXPECT_GT(initial, 1e-4) << "the untrained model should be visibly off";
  EXPECT_LT(last, initial / 10) << "initial " << initial << " final " << last;
  std::printf("position MSE %.3g m^2 -> %.3g m^2 (%.0fx)\n", initial, last, initial / last);
}

}  // namespace
}  // namespace layers::deepsd
