// Autoregressive rollouts with the registry's metrics per frame (see rollout.h).
#include "layers/train/rollout.h"

#include <torch/csrc/autograd/grad_mode.h>

#include <cmath>
#include <cstring>
#include <optional>

#include "layers/core/error.h"
#include "layers/core/progress.h"

namespace layers::train {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

geometry::Points points_of(const at::Tensor& t) {
  const at::Tensor c = t.detach().to(at::kCPU, at::kFloat).contiguous();
  geometry::Points p(c.size(0), 3);
  std::memcpy(p.data(), c.data_ptr<float>(), sizeof(float) * static_cast<std::size_t>(c.numel()));
  return p;
}

geometry::Faces faces_of(const at::Tensor& t) {
  const at::Tensor c = t.to(at::kCPU, at::kInt).contiguous();
  geometry::Faces f(c.size(0), 3);
  std::memcpy(f.data(), c.data_ptr<int>(), sizeof(int) * static_cast<std::size_t>(c.numel()));
  return f;
}

}  // namespace

double FrameMetrics::error_mm() const { return value.at(metrics::index_of(metrics::kError)).scene; }

RolloutResult rollout(zoo::Model& model, const zoo::SequenceStatic& seq, const FrameTensors& frames,
                      const RolloutOptions& options) {
  const std::int64_t last = frames.frames() - 1;
  const std::int64_t steps = options.steps < 0 ? last - options.start : options.steps;
  if (options.start < 1 || steps < 1 || options.start + steps > last)
    throw Error("rollout of sequence '" + seq.id + "': start row " + std::to_string(options.start) + " and " +
                std::to_string(steps) + " steps do not fit a window of " + std::to_string(frames.frames()) + " frames");
  torch::NoGradGuard no_grad;
  const std::vector<metrics::MetricDef> defs = metrics::registered();  // the list as the rollout starts
  const std::size_t error = metrics::index_of(metrics::kError);
  const geometry::Faces body_faces = faces_of(seq.body_faces);
  std::vector<geometry::Faces> garment_faces;
  std::vector<int> layers;
  for (const zoo::GarmentStatic& g : seq.garments) {
    garment_faces.push_back(faces_of(g.faces));
    layers.push_back(static_cast<int>(g.layer));
  }
  const auto meshes_of = [&](const std::vector<geometry::Points>& points) {
    std::vector<geometry::TriMesh> meshes;
    for (std::size_t g = 0; g < points.size(); ++g) meshes.push_back({points[g], garment_faces[g]});
    return meshes;
  };
  RolloutResult result;
  std::vector<std::vector<at::Tensor>> kept(seq.garments.size());
  std::vector<zoo::GarmentState> states = true_states(frames, options.start);
  // Each garment one frame before the predicted one: predicted and true.
  std::vector<geometry::Points> previous, previous_truth;
  for (const at::Tensor& g : frames.garments) previous.push_back(points_of(g[options.start]));
  previous_truth = previous;
  for (std::int64_t s = 0; s < steps; ++s) {
    const std::int64_t i = options.start + s;  // predicting row i + 1
    FrameMetrics m;
    m.frame = frames.first_frame + i + 1;
    m.value.assign(defs.size(), metrics::FrameValue{kNaN, {}});
    m.truth.assign(defs.size(), kNaN);
    // A frame at or after the divergence: the bound for the metrics that
    // count it (the error), nothing for the others.
    const auto record_diverged = [&] {
      m.diverged = true;
      for (std::size_t k = 0; k < defs.size(); ++k)
        m.value[k] =
            defs[k].diverged == metrics::Diverged::Bound
                ? metrics::FrameValue{options.diverge_mm, std::vector<double>(seq.garments.size(), options.diverge_mm)}
                : metrics::FrameValue{kNaN, {}};
      result.frames.push_back(m);
    };
    if (result.diverged_at >= 0) {
      record_diverged();
      continue;
    }
    Timer timer;
    zoo::StepOutput out = model.step(step_input(frames, i, states));
    result.model_seconds += timer.seconds();
    std::vector<geometry::Points> truth, predicted_points;
    for (const at::Tensor& g : frames.garments) truth.push_back(points_of(g[i + 1]));
    for (const at::Tensor& g : out.garments) predicted_points.push_back(points_of(g));
    std::optional<metrics::BodyFrame> body;
    if (options.rates) body.emplace(geometry::TriMesh{points_of(frames.body[i + 1]), body_faces});
    const metrics::FrameScene predicted(meshes_of(predicted_points), layers, &truth, &previous,
                                        body ? &*body : nullptr);
    m.value[error] = defs[error].compute(predicted);
    const double error_mm = m.value[error].scene;
    if (!std::isfinite(error_mm) || error_mm > options.diverge_mm) {
      result.diverged_at = m.frame;
      result.diverge_reason = std::isfinite(error_mm) ? "error " + std::to_string(error_mm) + " mm above the bound " +
                                                            std::to_string(options.diverge_mm) + " mm"
                                                      : "non-finite prediction";
      record_diverged();
      continue;
    }
    if (options.rates) {
      std::optional<metrics::FrameScene> true_scene;
      if (options.truth_collisions) true_scene.emplace(meshes_of(truth), layers, nullptr, &previous_truth, &*body);
      for (std::size_t k = 0; k < defs.size(); ++k) {
        if (k == error) continue;
        m.value[k] = defs[k].compute(predicted);
        if (defs[k].truth && true_scene) m.truth[k] = defs[k].compute(*true_scene).scene;
      }
    }
    result.frames.push_back(m);
    previous = std::move(predicted_points);
    previous_truth = std::move(truth);
    for (std::size_t k = 0; k < kept.size(); ++k) {
      if (options.keep_predictions) kept[k].push_back(out.garments[k].detach());
      states[k] = {states[k].current, out.garments[k].detach()};
    }
  }
  if (options.keep_predictions) {
    // From the divergence on, the last finite prediction is held (the
    // metrics record the divergence; the file stays valid and viewable).
    for (std::size_t k = 0; k < kept.size(); ++k) {
      while (static_cast<std::int64_t>(kept[k].size()) < steps) kept[k].push_back(states[k].current);
      result.predictions.push_back(at::stack(kept[k]).to(at::kCPU));
    }
  }
  return result;
}

}  // namespace layers::train
