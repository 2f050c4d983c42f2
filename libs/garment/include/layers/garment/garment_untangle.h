// layers/garment/garment_untangle.h -- a garment built folded onto itself,
// smoothed where it crosses itself (docs/garments.md, "How a garment is
// made", step 8).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "layers/geometry/mesh.h"

namespace layers::garment {

constexpr int kUntangleRounds = 10;

// The clearance pushes of a build move vertices along the normals of
// their nearest skin vertices, which converge over a concave stretch (the
// spine's groove, a shoulder blade) and can fold a panel onto itself; and
// an opening that turns a corner in 3D where its UV outline rounds it (a
// back neckline's flat bottom) can fold a face over that corner. Each
// round finds the faces that pass through another face of the garment
// (geometry::self_crossings), smooths the vertices of those faces and of
// two rings around them (three sweeps, each vertex to the mean of its
// neighbours) and calls `push_out` (the clearance again). The first
// kUntangleRounds rounds keep the openings (`boundary`, one flag per
// vertex) where they are; if crossings remain, up to kUntangleRounds more
// move an opening vertex too, to the mean of its two neighbours along the
// opening, which rounds the opening's corner (a flagged vertex with fewer
// than two stays). Returns the crossing face
// pairs left (0 on success). A garment that does not cross itself is not
// touched.
std::int64_t untangle(geometry::Points& vertices, const geometry::Faces& faces,
                      const std::vector<std::uint8_t>& boundary, const std::function<void()>& push_out);

}  // namespace layers::garment
