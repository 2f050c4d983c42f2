// glb_builder.h -- what the two glTF writers share (data's own): the
// binary chunk with its buffer views and accessors (vertex data with
// buffer-view targets and POSITION bounds, animation data without
// targets, as the Khronos validator asks) and the GLB container.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace layers::data::glb {

using json = nlohmann::json;

constexpr int kFloat = 5126, kUInt = 5125, kUShort = 5123;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

struct Builder {
  std::string bin;
  json views = json::array(), accessors = json::array();

  // A buffer view over `bytes` bytes (target 0: none), 4-byte aligned.
  int view(const void* data, std::size_t bytes, int target);
  // An accessor of `count` elements of `type` ("SCALAR", "VEC3", "MAT4", ...).
  int accessor(int view, int component, std::size_t count, const char* type);
  // VEC3 float vertex data with its bounds (POSITION and morph targets).
  int vec3(const std::vector<float>& xyz);
  int indices(const std::vector<std::int32_t>& faces);
  // Animation data of `type` (no target); `bounds`: min and max (keyframe times).
  int floats(const std::vector<float>& values, const char* type, bool bounds);
  int scalars(const std::vector<float>& values, bool bounds) { return floats(values, "SCALAR", bounds); }
};

// The GLB file: header, the JSON chunk (`doc` with its one buffer's
// length set here) and the binary chunk.
std::string container(json doc, std::string bin);

}  // namespace layers::data::glb
