// refused_where.h (private to layers::generate) -- where on the garments a
// refused scene broke: the most stretched edges of a stored frame, each
// with its garment, vertices, stretch, position and the body joint nearest
// to it, and where garments cross the body (outside its pinch zones) or
// each other, as lines of the scene's `.refused.yaml` (`--keep-refused`).
#pragma once

#include <string>
#include <vector>

#include "layers/data/sequence.h"

namespace layers::generate {

// The `count` most stretched edges (length over rest length - 1) of frame
// `frame` over all garments of `seq`, most stretched first, e.g.
// "dress: edge 120-121 stretched 107.12% at (0.312, 1.224, 0.051) m, nearest joint LeftForeArm".
std::vector<std::string> most_stretched_edges(const data::SequenceData& seq, int frame, int count);

// Where the garments of frame `frame` cross: per garment, its faces through
// the body outside the body's pinch zones (geometry::pinch_zones_under with
// `pinch_distance`), and per pair of garments the first one's faces through
// the second, grouped by the body joint nearest to each face, the `count`
// largest groups with their centre, e.g. "dress through the body: 12
// faces, near LeftUpLeg 8 at (0.061, 0.702, 0.083) m, near Hips 4 at
// (...) m". Nothing when nothing crosses.
std::vector<std::string> crossing_places(const data::SequenceData& seq, int frame, double pinch_distance, int count);

// The stored frame whose most stretched edge is stretched most (0 when
// `seq` has no frame).
int most_stretched_frame(const data::SequenceData& seq);

}  // namespace layers::generate
