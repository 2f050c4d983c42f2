// Conversion of a generated body into LAYERS-H5 arrays (see body_data.h).
#include "layers/generate/body_data.h"

#include "layers/body/body_arrays.h"
#include "layers/body/skeleton.h"
#include "layers/body/skinning.h"
#include "layers/core/error.h"

namespace layers::generate {

namespace {
// Frames [first, first + count) of a [T, ...] array with `per_frame` values a frame.
template <class T>
std::vector<T> frames(const std::vector<T>& all, std::size_t per_frame, int first, int count) {
  return std::vector<T>(all.begin() + static_cast<std::ptrdiff_t>(per_frame * first),
                        all.begin() + static_cast<std::ptrdiff_t>(per_frame * (first + count)));
}
}  // namespace

void fill_body(data::SequenceData& seq, const motion::GeneratedBody& generated, int first, int count,
               const Eigen::Isometry3d& tpose_placement) {
  const motion::BodySequence& s = generated.sequence;
  if (count < 0) count = s.num_frames - first;
  if (first < 0 || first + count > s.num_frames)
    throw Error("fill_body: frames [" + std::to_string(first) + ", " + std::to_string(first + count) +
                ") outside the body sequence of " + std::to_string(s.num_frames) + " frames");
  const body::BodyArrays arrays = body::body_arrays(generated.body);
  seq.n_frames = count;
  seq.motion = s.motion;
  // A user's body has no shape parameters of ours.
  if (generated.body.file.empty())
    seq.shape = {{"gender", generated.body.shape.gender},
                 {"muscle", generated.body.shape.muscle},
                 {"weight", generated.body.shape.weight},
                 {"height", generated.body.shape.height}};
  data::BodyData& b = seq.body;
  b.faces.assign(arrays.faces.begin(), arrays.faces.end());
  b.joint_names = arrays.joint_names;
  b.joint_parents.assign(arrays.joint_parents.begin(), arrays.joint_parents.end());
  b.skin_index.assign(arrays.skin_index.begin(), arrays.skin_index.end());
  b.skin_weight = arrays.skin_weight;
  const std::size_t vertices = static_cast<std::size_t>(s.num_vertices),
                    joints = static_cast<std::size_t>(s.num_joints);
  b.positions = frames(s.positions, vertices * 3, first, count);
  b.root = frames(s.root, 3, first, count);
  b.root_rot = frames(s.root_rot, 4, first, count);
  b.joints = frames(s.joints, joints * 12, first, count);
  // The T-pose the garments were made in, placed where they were put.
  body::JointTransforms tpose = body::forward_kinematics(generated.body.skeleton, generated.body.t_pose);
  const body::Quat turn(tpose_placement.rotation());
  for (std::size_t j = 0; j < tpose.rotation.size(); ++j) {
    tpose.rotation[j] = turn * tpose.rotation[j];
    tpose.position[j] = tpose_placement * tpose.position[j];
  }
  b.tpose_joints.resize(joints * 12);
  body::joint_matrices(tpose, b.tpose_joints.data());
}

data::SequenceData body_only_sequence(const motion::GeneratedBody& generated, const std::string& id,
                                      std::uint64_t seed) {
  data::SequenceData seq;
  seq.id = id;
  seq.seed = seed;
  fill_body(seq, generated);
  const auto frames = static_cast<std::size_t>(seq.n_frames);
  seq.wind.strength.assign(frames, 0.0f);
  seq.wind.rotation.assign(frames * 4, 0.0f);
  for (std::size_t t = 0; t < frames; ++t) seq.wind.rotation[t * 4] = 1.0f;
  return seq;
}

}  // namespace layers::generate
