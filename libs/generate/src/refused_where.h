// refused_where.h (private to layers::generate) -- where on the garments a
// refused scene broke: the most stretched edges of a stored frame, each
// with its garment, vertices, stretch, position and the body joint nearest
// to it, as lines of the scene's `.refused.yaml` (`--keep-refused`).
#pragma once

#include <string>
#include <vector>

#include "layers/data/sequence.h"

namespace layers::generate {

// The `count` most stretched edges (length over rest length - 1) of frame
// `frame` over all garments of `seq`, most stretched first, e.g.
// "dress: edge 120-121 stretched 107.12% at (0.312, 1.224, 0.051) m, nearest joint LeftForeArm".
std::vector<std::string> most_stretched_edges(const data::SequenceData& seq, int frame, int count);

// The stored frame whose most stretched edge is stretched most (0 when
// `seq` has no frame).
int most_stretched_frame(const data::SequenceData& seq);

}  // namespace layers::generate
