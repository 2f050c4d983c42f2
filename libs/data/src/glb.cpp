// A sequence as a binary glTF 2.0 file with morph-target frames (see glb.h),
// and the buffer builder and GLB container both writers use (glb_builder.h).
#include "layers/data/glb.h"

#include "glb_builder.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <limits>

#include "layers/core/error.h"

namespace layers::data {
namespace glb {
int Builder::view(const void* data, std::size_t bytes, int target) {
  while (bin.size() % 4) bin.push_back('\0');
  json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
  if (target) v["target"] = target;
  views.push_back(v);
  bin.append(static_cast<const char*>(data), bytes);
  return static_cast<int>(views.size()) - 1;
}

int Builder::accessor(int view, int component, std::size_t count, const char* type) {
  accessors.push_back({{"bufferView", view}, {"componentType", component}, {"count", count}, {"type", type}});
  return static_cast<int>(accessors.size()) - 1;
}

int Builder::vec3(const std::vector<float>& xyz) {
  float lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = std::numeric_limits<float>::max(), hi[a] = -lo[a];
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max(hi[i % 3], xyz[i]);
  }
  const int a = accessor(view(xyz.data(), xyz.size() * sizeof(float), kArrayBuffer), kFloat, xyz.size() / 3, "VEC3");
  accessors[a]["min"] = {lo[0], lo[1], lo[2]};
  accessors[a]["max"] = {hi[0], hi[1], hi[2]};
  return a;
}

int Builder::indices(const std::vector<std::int32_t>& faces) {
  std::vector<std::uint32_t> u(faces.begin(), faces.end());
  return accessor(view(u.data(), u.size() * sizeof(std::uint32_t), kElementArrayBuffer), kUInt, u.size(), "SCALAR");
}

int Builder::floats(const std::vector<float>& values, const char* type, bool bounds) {
  const std::size_t per = std::string(type) == "SCALAR" ? 1
                          : std::string(type) == "VEC3" ? 3
                          : std::string(type) == "VEC4" ? 4
                                                        : 16;
  const int a = accessor(view(values.data(), values.size() * sizeof(float), 0), kFloat, values.size() / per, type);
  if (bounds) {
    accessors[a]["min"] = {*std::min_element(values.begin(), values.end())};
    accessors[a]["max"] = {*std::max_element(values.begin(), values.end())};
  }
  return a;
}

namespace {
void append_u32(std::string& out, std::uint32_t v) {
  char b[4];
  std::memcpy(b, &v, 4);
  out.append(b, 4);
}
}  // namespace

std::string container(json doc, std::string bin) {
  while (bin.size() % 4) bin.push_back('\0');
  doc["buffers"] = json::array({{{"byteLength", bin.size()}}});
  std::string text = doc.dump();
  while (text.size() % 4) text.push_back(' ');
  std::string out;
  append_u32(out, 0x46546C67u);  // "glTF"
  append_u32(out, 2);
  append_u32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
  append_u32(out, static_cast<std::uint32_t>(text.size()));
  append_u32(out, 0x4E4F534Au);  // "JSON"
  out += text;
  append_u32(out, static_cast<std::uint32_t>(bin.size()));
  append_u32(out, 0x004E4942u);  // "BIN\0"
  out += bin;
  return out;
}

}  // namespace glb

namespace {

using glb::Builder;
using glb::json;

}  // namespace

std::string glb_bytes(const std::vector<GlbMesh>& meshes, double fps, std::int64_t frames_per_chunk) {
  if (meshes.empty() || meshes.front().frames.empty()) throw Error("glb: no mesh or no frame to write");
  if (frames_per_chunk < 2) throw Error("glb: frames_per_chunk must be at least 2");
  const std::size_t frames = meshes.front().frames.size();
  const std::size_t per_chunk = static_cast<std::size_t>(frames_per_chunk);
  const std::size_t chunks = (frames + per_chunk - 1) / per_chunk;
  Builder b;
  json nodes = json::array(), roots = json::array(), gltf_meshes = json::array(), channels = json::array(),
       samplers = json::array();
  auto time_of = [&](std::size_t k) { return static_cast<float>(static_cast<double>(k) / fps); };
  // Keyframe times of each chunk's frames, shared by every mesh.
  std::vector<int> chunk_times(chunks, -1);
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t first = c * per_chunk, last = std::min(frames, first + per_chunk);
    if (last - first < 2) continue;
    std::vector<float> times;
    for (std::size_t k = first; k < last; ++k) times.push_back(time_of(k));
    chunk_times[c] = b.scalars(times, true);
  }
  // Visibility of chunk c (node scale, STEP): 1 over its frames, 0 elsewhere.
  auto add_visibility = [&](int node, std::size_t c) {
    const std::size_t first = c * per_chunk, last = std::min(frames, first + per_chunk);
    std::vector<float> times, scales;
    auto key = [&](std::size_t k, float s) {
      times.push_back(time_of(k));
      scales.insert(scales.end(), {s, s, s});
    };
    if (first > 0) key(0, 0.0f);
    key(first, 1.0f);
    if (last < frames) key(last, 0.0f);
    const int input = b.scalars(times, true);
    samplers.push_back({{"input", input}, {"output", b.floats(scales, "VEC3", false)}, {"interpolation", "STEP"}});
    channels.push_back(
        {{"sampler", static_cast<int>(samplers.size()) - 1}, {"target", {{"node", node}, {"path", "scale"}}}});
  };
  for (const GlbMesh& mesh : meshes) {
    if (mesh.frames.size() != frames) throw Error("glb: mesh '" + mesh.name + "' has another frame count");
    std::vector<int> chunk_nodes;
    const int indices = b.indices(mesh.faces);  // one accessor for every chunk of the mesh
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::size_t first = c * per_chunk, last = std::min(frames, first + per_chunk);
      const std::vector<float>& base = mesh.frames[first];
      json primitive = {{"attributes", {{"POSITION", b.vec3(base)}}}, {"indices", indices}, {"mode", 4}};
      json targets = json::array();
      for (std::size_t k = first + 1; k < last; ++k) {
        if (mesh.frames[k].size() != base.size()) throw Error("glb: mesh '" + mesh.name + "' changes its vertex count");
        std::vector<float> offset(base.size());
        for (std::size_t i = 0; i < base.size(); ++i) offset[i] = mesh.frames[k][i] - base[i];
        targets.push_back({{"POSITION", b.vec3(offset)}});
      }
      const std::string name = chunks == 1 ? mesh.name : mesh.name + ".chunk" + std::to_string(c);
      json gm = {{"name", name}};
      if (!targets.empty()) {
        primitive["targets"] = targets;
        gm["weights"] = std::vector<float>(targets.size(), 0.0f);
      }
      gm["primitives"] = json::array({primitive});
      gltf_meshes.push_back(gm);
      const int node = static_cast<int>(nodes.size());
      json n = {{"name", name}, {"mesh", static_cast<int>(gltf_meshes.size()) - 1}};
      if (c > 0) n["scale"] = {0.0, 0.0, 0.0};
      nodes.push_back(n);
      chunk_nodes.push_back(node);
      if (!targets.empty()) {
        // Keyframe k of the chunk: target k (1-based among its frames) at weight 1, the others 0.
        const std::size_t n_frames = last - first, n_targets = n_frames - 1;
        std::vector<float> weights(n_frames * n_targets, 0.0f);
        for (std::size_t k = 1; k < n_frames; ++k) weights[k * n_targets + (k - 1)] = 1.0f;
        samplers.push_back(
            {{"input", chunk_times[c]}, {"output", b.scalars(weights, false)}, {"interpolation", "STEP"}});
        channels.push_back(
            {{"sampler", static_cast<int>(samplers.size()) - 1}, {"target", {{"node", node}, {"path", "weights"}}}});
      }
      if (chunks > 1) add_visibility(node, c);
    }
    if (chunks == 1) {
      roots.push_back(chunk_nodes.front());
    } else {
      roots.push_back(static_cast<int>(nodes.size()));
      nodes.push_back({{"name", mesh.name}, {"children", chunk_nodes}});
    }
  }
  json doc = {{"asset", {{"version", "2.0"}, {"generator", "layers export --format glb"}}},
              {"scene", 0},
              {"scenes", json::array({{{"nodes", roots}}})},
              {"nodes", nodes},
              {"meshes", gltf_meshes},
              {"bufferViews", b.views},
              {"accessors", b.accessors}};
  if (!channels.empty())
    doc["animations"] = json::array({{{"name", "frames"}, {"channels", channels}, {"samplers", samplers}}});
  return glb::container(std::move(doc), std::move(b.bin));
}

}  // namespace layers::data
