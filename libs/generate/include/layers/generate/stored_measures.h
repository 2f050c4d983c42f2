// layers/generate/stored_measures.h -- the generator's validation measures
// (sim/measures.h: H- and L-penetration, stretch, non-finite values)
// recomputed from a written sequence, frame by frame: an independent check
// of stored ground truth (`layers validate --physics`).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "layers/data/sequence.h"
#include "layers/geometry/mesh.h"
#include "layers/sim/measures.h"

namespace layers::generate {

// One stored frame as the measures take it: the body mesh and every
// garment (positions, faces, edges with the rest lengths of its stored rest
// shape, outer = dataset layer 1).
struct StoredFrame {
  geometry::TriMesh body;
  std::vector<sim::MeasuredGarment> garments;
};

// Calls visit(frame, stored) for frames 0 .. n_frames-1 of `seq`.
void for_each_stored_frame(const data::SequenceData& seq,
                           const std::function<void(std::int64_t, const StoredFrame&)>& visit);

// Frame `frame` of `seq` alone (layers::Error outside 0 .. n_frames-1).
StoredFrame stored_frame(const data::SequenceData& seq, std::int64_t frame);

}  // namespace layers::generate
