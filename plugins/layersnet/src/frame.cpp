// LayersNet's per-step moving frames (see frame.h).
#include "frame.h"

#include "layers/zoo/rotations.h"

namespace layers::layersnet {

StepFrames::StepFrames(const zoo::StepInput& in, bool heading) : root_(in.root.to(at::kFloat)) {
  if (!heading) return;
  heading_ = zoo::heading_quaternions(in.root_rot.to(at::kFloat));
  axes_ = zoo::rotation_matrices(heading_);
}

// Row vectors: R^T v for each row v is v R.
at::Tensor StepFrames::vectors_to_local(std::int64_t k, const at::Tensor& vectors) const {
  return axes_.defined() ? at::matmul(vectors, axes_[k]) : vectors;
}

at::Tensor StepFrames::to_local(std::int64_t k, const at::Tensor& points) const {
  return vectors_to_local(k, points - root_[k]);
}

at::Tensor StepFrames::to_world(std::int64_t k, const at::Tensor& local) const {
  return (axes_.defined() ? at::matmul(local, axes_[k].t()) : local) + root_[k];
}

at::Tensor StepFrames::wind_to_local(const at::Tensor& wind_rotation) const {
  const at::Tensor q = wind_rotation.to(at::kFloat);
  if (!heading_.defined()) return q;
  return zoo::quaternion_multiply(zoo::quaternion_conjugate(heading_[2]), q);
}

}  // namespace layers::layersnet
