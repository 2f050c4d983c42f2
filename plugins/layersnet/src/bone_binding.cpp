// Binding garment vertices to the skeleton's bones (see joint_binding.h).
#include "joint_binding.h"

#include <algorithm>
#include <string>
#include <vector>

#include "layers/core/error.h"

namespace layers::layersnet {

JointBinding bind_to_bones(const zoo::SequenceStatic& s) {
  const std::string where = "sequence '" + s.id + "'";
  if (!s.tpose_joints.defined() || !s.joint_parents.defined())
    throw InputError(where, s.tpose_joints.defined() ? "joint_parents" : "tpose_joints",
                     "the skeleton's T-pose joints and parents (LayersNet base 'bones')", "none");
  std::vector<at::Tensor> rest;
  for (const zoo::GarmentStatic& g : s.garments) rest.push_back(g.rest.to(at::kFloat));
  const at::Tensor x = at::cat(rest);  // [V,3]
  // Bones: every joint with a parent, from the parent (which moves it) to the joint.
  const at::Tensor parents = s.joint_parents.to(x.device(), at::kLong);
  const at::Tensor child = at::nonzero((parents >= 0) & (parents < parents.size(0))).flatten();
  if (child.numel() == 0) throw InputError(where, "joint_parents", "at least one bone (a joint with a parent)", "none");
  const at::Tensor owners = parents.index_select(0, child);
  const at::Tensor position = s.tpose_joints.select(2, 3).to(x.device(), at::kFloat);  // [J,3]
  const at::Tensor a = position.index_select(0, owners), b = position.index_select(0, child);

  // Distance of every vertex to every segment a -> b: [V,B].
  const at::Tensor ab = b - a;
  const at::Tensor ax = x.unsqueeze(1) - a.unsqueeze(0);
  const at::Tensor length2 = (ab * ab).sum(1).clamp_min(1e-12);
  const at::Tensor along = ((ax * ab.unsqueeze(0)).sum(2) / length2).clamp(0, 1);
  const at::Tensor distance = (ax - along.unsqueeze(2) * ab.unsqueeze(0)).norm(2, 2);

  const std::int64_t k = std::min<std::int64_t>(2, child.numel());
  const auto [nearest, bone] = distance.topk(k, 1, /*largest=*/false);
  JointBinding out;
  out.joint = owners.index_select(0, bone.flatten()).view_as(bone);
  out.weight = at::softmax(-(nearest - nearest.select(1, 0).unsqueeze(1)) / kBoneBlend, 1);
  return out;
}

}  // namespace layers::layersnet
