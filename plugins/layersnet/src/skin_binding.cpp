// Binding garment vertices to the body's skinning (see joint_binding.h).
#include <string>
#include <vector>

#include "joint_binding.h"
#include "layers/core/error.h"
#include "layers/zoo/skinning.h"

namespace layers::layersnet {
namespace {

std::string where(const zoo::SequenceStatic& s) { return "sequence '" + s.id + "'"; }

}  // namespace

void check_skin_data(const zoo::SequenceStatic& s) {
  const std::string what = " (LayersNet base 'skin')";
  if (!s.skin_index.defined())
    throw InputError(where(s), "skin_index", "the body's skinning joints [Vb,4]" + what, "none");
  if (!s.skin_weight.defined())
    throw InputError(where(s), "skin_weight", "the body's skinning weights [Vb,4]" + what, "none");
  if (!s.tpose_joints.defined())
    throw InputError(where(s), "tpose_joints", "the T-pose the garments were made in [J,3,4]" + what, "none");
}

JointBinding bind_to_skin(const zoo::SequenceStatic& s, const at::Tensor& body_t, const at::Tensor& joints_t) {
  check_skin_data(s);
  at::NoGradGuard no_grad;
  const at::Tensor body = body_t.detach().to(at::kCPU, at::kFloat);
  const at::Tensor index = s.skin_index.to(at::kCPU, at::kLong);
  const at::Tensor weight = s.skin_weight.to(at::kCPU, at::kFloat);
  const std::int64_t vb = body.size(0), nj = joints_t.size(0);
  if (index.size(0) != vb)
    throw InputError(where(s), "skin_index", std::to_string(vb) + " rows (the body's vertices)",
                     std::to_string(index.size(0)));
  if (s.tpose_joints.size(0) != nj)
    throw InputError(where(s), "tpose_joints", std::to_string(nj) + " joints (as body/joints)",
                     std::to_string(s.tpose_joints.size(0)));
  if (vb == 0) throw InputError(where(s), "body", "at least one body vertex to bind to", "none");
  const std::int64_t lo = index.min().item<std::int64_t>(), hi = index.max().item<std::int64_t>();
  if (lo < 0 || hi >= nj)
    throw InputError(where(s), "skin_index", "joint indices in [0, " + std::to_string(nj) + ")",
                     std::to_string(lo < 0 ? lo : hi));
  const at::Tensor sums = weight.sum(1, /*keepdim=*/true);
  const double smallest = sums.min().item<double>();
  if (!(smallest > 0))
    throw InputError(where(s), "skin_weight", "a positive weight sum for every body vertex",
                     "a sum of " + std::to_string(smallest));
  const at::Tensor maps =
      zoo::tpose_to_frame(s.tpose_joints.to(at::kCPU, at::kFloat), joints_t.detach().to(at::kCPU, at::kFloat));
  const double det = zoo::smallest_blend_determinant(index, weight, maps);
  if (!(det > 1e-6))
    throw InputError(where(s), "skin_weight", "blended joint maps that can be inverted (|det| > 1e-6)",
                     "|det| " + std::to_string(det));
  // The body brought back to the T-pose; each garment vertex's rest
  // position bound to the skinning of its nearest T-pose body vertex.
  const at::Tensor tpose_body = zoo::unskin(body, index, weight, maps);
  std::vector<at::Tensor> rest;
  for (const zoo::GarmentStatic& g : s.garments) rest.push_back(g.rest.to(at::kCPU, at::kFloat));
  const zoo::SkinBinding b = zoo::bind_to_nearest_skin(at::cat(rest), tpose_body, index, weight);
  return {b.joint.to(body_t.device()), b.weight.to(body_t.device())};
}

}  // namespace layers::layersnet
