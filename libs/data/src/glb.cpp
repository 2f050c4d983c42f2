// A sequence as a binary glTF 2.0 file with morph-target frames (see glb.h).
#include "layers/data/glb.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <limits>

#include "layers/core/error.h"

namespace layers::data {
namespace {

using json = nlohmann::json;

constexpr int kFloat = 5126, kUInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// The binary chunk and the buffer views / accessors that point into it.
struct Builder {
  std::string bin;
  json views = json::array(), accessors = json::array();

  int view(const void* data, std::size_t bytes, int target) {
    while (bin.size() % 4) bin.push_back('\0');
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}, {"target", target}});
    bin.append(static_cast<const char*>(data), bytes);
    return static_cast<int>(views.size()) - 1;
  }
  // VEC3 float accessor with its bounds (POSITION and its morph targets).
  int vec3(const std::vector<float>& xyz) {
    float lo[3], hi[3];
    for (int a = 0; a < 3; ++a) lo[a] = std::numeric_limits<float>::max(), hi[a] = -lo[a];
    for (std::size_t i = 0; i < xyz.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], xyz[i]);
      hi[i % 3] = std::max(hi[i % 3], xyz[i]);
    }
    const int v = view(xyz.data(), xyz.size() * sizeof(float), kArrayBuffer);
    accessors.push_back({{"bufferView", v},
                         {"componentType", kFloat},
                         {"count", xyz.size() / 3},
                         {"type", "VEC3"},
                         {"min", {lo[0], lo[1], lo[2]}},
                         {"max", {hi[0], hi[1], hi[2]}}});
    return static_cast<int>(accessors.size()) - 1;
  }
  int indices(const std::vector<std::int32_t>& faces) {
    std::vector<std::uint32_t> u(faces.begin(), faces.end());
    const int v = view(u.data(), u.size() * sizeof(std::uint32_t), kElementArrayBuffer);
    accessors.push_back({{"bufferView", v}, {"componentType", kUInt}, {"count", u.size()}, {"type", "SCALAR"}});
    return static_cast<int>(accessors.size()) - 1;
  }
  // Animation data (no buffer-view target: not vertex data).
  int scalars(const std::vector<float>& values, bool bounds) {
    while (bin.size() % 4) bin.push_back('\0');
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", values.size() * sizeof(float)}});
    bin.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
    json a = {{"bufferView", static_cast<int>(views.size()) - 1},
              {"componentType", kFloat},
              {"count", values.size()},
              {"type", "SCALAR"}};
    if (bounds) {
      a["min"] = {*std::min_element(values.begin(), values.end())};
      a["max"] = {*std::max_element(values.begin(), values.end())};
    }
    accessors.push_back(a);
    return static_cast<int>(accessors.size()) - 1;
  }
};

void append_u32(std::string& out, std::uint32_t v) {
  char b[4];
  std::memcpy(b, &v, 4);
  out.append(b, 4);
}

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
    while (b.bin.size() % 4) b.bin.push_back('\0');
    b.views.push_back({{"buffer", 0}, {"byteOffset", b.bin.size()}, {"byteLength", scales.size() * sizeof(float)}});
    b.bin.append(reinterpret_cast<const char*>(scales.data()), scales.size() * sizeof(float));
    b.accessors.push_back({{"bufferView", static_cast<int>(b.views.size()) - 1},
                           {"componentType", kFloat},
                           {"count", times.size()},
                           {"type", "VEC3"}});
    samplers.push_back(
        {{"input", input}, {"output", static_cast<int>(b.accessors.size()) - 1}, {"interpolation", "STEP"}});
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
  while (b.bin.size() % 4) b.bin.push_back('\0');
  json doc = {{"asset", {{"version", "2.0"}, {"generator", "layers export --format glb"}}},
              {"scene", 0},
              {"scenes", json::array({{{"nodes", roots}}})},
              {"nodes", nodes},
              {"meshes", gltf_meshes},
              {"buffers", json::array({{{"byteLength", b.bin.size()}}})},
              {"bufferViews", b.views},
              {"accessors", b.accessors}};
  if (!channels.empty())
    doc["animations"] = json::array({{{"name", "frames"}, {"channels", channels}, {"samplers", samplers}}});
  std::string text = doc.dump();
  while (text.size() % 4) text.push_back(' ');
  std::string out;
  append_u32(out, 0x46546C67u);  // "glTF"
  append_u32(out, 2);
  append_u32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + b.bin.size()));
  append_u32(out, static_cast<std::uint32_t>(text.size()));
  append_u32(out, 0x4E4F534Au);  // "JSON"
  out += text;
  append_u32(out, static_cast<std::uint32_t>(b.bin.size()));
  append_u32(out, 0x004E4942u);  // "BIN\0"
  out += b.bin;
  return out;
}

}  // namespace layers::data
