// Conversion of a generated body into LAYERS-H5 arrays (see body_data.h).
#include "layers/generate/body_data.h"

namespace layers::generate {

void fill_body(data::SequenceData& seq, const scene::GeneratedBody& generated) {
  const scene::BodySequence& s = generated.sequence;
  const scene::BodyArrays arrays = scene::body_arrays(generated.body);
  seq.n_frames = s.num_frames;
  seq.motion = s.motion;
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
  b.positions = s.positions;
  b.root = s.root;
  b.root_rot = s.root_rot;
  b.joints = s.joints;
}

data::SequenceData body_only_sequence(const scene::GeneratedBody& generated, const std::string& id,
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
