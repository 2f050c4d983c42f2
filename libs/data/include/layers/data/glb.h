// layers/data/glb.h -- a sequence as one binary glTF 2.0 file (GLB) that
// Blender and three.js play: one mesh node per body and garment, the
// first exported frame as the mesh and every later frame as a morph
// target (POSITION offsets), played by one weights animation per node
// (STEP interpolation, one keyframe per frame at the format's 30 fps:
// frame k has target k at weight 1, frame 0 none). Metres, y up, as the
// format. Buffer views carry their targets and POSITION accessors their
// bounds, as the Khronos validator asks.
//
// Long sequences are cut into chunks of `frames_per_chunk` frames, so the
// weights (frames x targets per mesh) grow linearly, not quadratically:
// each body and garment is then a node named as the mesh whose children
// "<name>.chunk<c>" each hold their frames as above, and a STEP scale
// animation shows one chunk at a time (scale 1 over its frames, 0
// elsewhere).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace layers::data {

struct GlbMesh {
  std::string name;
  std::vector<std::int32_t> faces;         // triangles, [F*3]
  std::vector<std::vector<float>> frames;  // per frame, [V*3] positions
};

// Frames per chunk of `layers export --format glb` unless --glb-chunk says
// otherwise: 4 s at 30 fps.
inline constexpr std::int64_t kGlbFramesPerChunk = 120;

// The GLB's bytes for `meshes` (all with the same frame count, at least
// one frame). Throws layers::Error on inconsistent input or fewer than 2
// frames per chunk.
std::string glb_bytes(const std::vector<GlbMesh>& meshes, double fps,
                      std::int64_t frames_per_chunk = kGlbFramesPerChunk);

}  // namespace layers::data
