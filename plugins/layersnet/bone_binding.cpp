// Binding garment vertices to the skeleton's bones (see bone_binding.h).
#include "bone_binding.h"

#include <string>
#include <vector>

#include "layers/core/error.h"

namespace layers::layersnet {

BoneBinding bind_to_bones(const zoo::SequenceStatic& s) {
  const std::string where = "sequence '" + s.id + "'";
  if (!s.tpose_joints.defined() || !s.joint_parents.defined())
    throw InputError(where, s.tpose_joints.defined() ? "joint_parents" : "tpose_joints",
                     "the skeleton's T-pose joints and parents (LayersNet base 'bones')", "none");
  const at::Tensor parents = s.joint_parents.to(at::kCPU, at::kLong);
  const at::Tensor position = s.tpose_joints.select(2, 3).to(at::kFloat);  // [J,3]
  std::vector<std::int64_t> child, owner;
  for (std::int64_t j = 0; j < parents.size(0); ++j) {
    const std::int64_t p = parents[j].item<std::int64_t>();
    if (p >= 0 && p < parents.size(0)) {
      child.push_back(j);
      owner.push_back(p);
    }
  }
  if (child.empty())
    throw InputError(where, "joint_parents", "at least one bone (a joint with a parent)", "none");
  std::vector<at::Tensor> rest;
  for (const zoo::GarmentStatic& g : s.garments) rest.push_back(g.rest.to(at::kFloat));
  const at::Tensor x = at::cat(rest);  // [V,3]
  const at::Device dev = x.device();
  const at::Tensor owners = at::tensor(owner, at::kLong).to(dev);
  const at::Tensor a = position.index_select(0, owners.to(position.device())).to(dev);
  const at::Tensor b = position.index_select(0, at::tensor(child, at::kLong).to(position.device())).to(dev);

  // Distance of every vertex to every segment a -> b: [V,B].
  const at::Tensor ab = b - a;
  const at::Tensor ax = x.unsqueeze(1) - a.unsqueeze(0);
  const at::Tensor length2 = (ab * ab).sum(1).clamp_min(1e-12);
  const at::Tensor along = ((ax * ab.unsqueeze(0)).sum(2) / length2).clamp(0, 1);
  const at::Tensor distance = (ax - along.unsqueeze(2) * ab.unsqueeze(0)).norm(2, 2);

  const std::int64_t k = std::min<std::int64_t>(2, static_cast<std::int64_t>(child.size()));
  const auto [nearest, bone] = distance.topk(k, 1, /*largest=*/false);
  BoneBinding out;
  out.joint = owners.index_select(0, bone.flatten()).view_as(bone);
  out.weight = at::softmax(-(nearest - nearest.select(1, 0).unsqueeze(1)) / kBoneBlend, 1);
  return out;
}

}  // namespace layers::layersnet
