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

std::string glb_bytes(const std::vector<GlbMesh>& meshes, double fps) {
  if (meshes.empty() || meshes.front().frames.empty()) throw Error("glb: no mesh or no frame to write");
  const std::size_t frames = meshes.front().frames.size();
  Builder b;
  json nodes = json::array(), gltf_meshes = json::array(), channels = json::array(), samplers = json::array();
  std::vector<float> times(frames);
  for (std::size_t k = 0; k < frames; ++k) times[k] = static_cast<float>(static_cast<double>(k) / fps);
  const int time_accessor = frames > 1 ? b.scalars(times, true) : -1;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const GlbMesh& mesh = meshes[m];
    if (mesh.frames.size() != frames) throw Error("glb: mesh '" + mesh.name + "' has another frame count");
    const std::vector<float>& base = mesh.frames.front();
    json primitive = {{"attributes", {{"POSITION", b.vec3(base)}}}, {"indices", b.indices(mesh.faces)}, {"mode", 4}};
    json targets = json::array();
    for (std::size_t k = 1; k < frames; ++k) {
      if (mesh.frames[k].size() != base.size()) throw Error("glb: mesh '" + mesh.name + "' changes its vertex count");
      std::vector<float> offset(base.size());
      for (std::size_t i = 0; i < base.size(); ++i) offset[i] = mesh.frames[k][i] - base[i];
      targets.push_back({{"POSITION", b.vec3(offset)}});
    }
    json gm = {{"name", mesh.name}};
    if (!targets.empty()) {
      primitive["targets"] = targets;
      gm["weights"] = std::vector<float>(frames - 1, 0.0f);
    }
    gm["primitives"] = json::array({primitive});
    gltf_meshes.push_back(gm);
    nodes.push_back({{"name", mesh.name}, {"mesh", static_cast<int>(m)}});
    if (frames > 1) {
      // Keyframe k: target k (1-based among frames) at weight 1, the others 0.
      std::vector<float> weights(frames * (frames - 1), 0.0f);
      for (std::size_t k = 1; k < frames; ++k) weights[k * (frames - 1) + (k - 1)] = 1.0f;
      samplers.push_back({{"input", time_accessor}, {"output", b.scalars(weights, false)}, {"interpolation", "STEP"}});
      channels.push_back({{"sampler", static_cast<int>(samplers.size()) - 1},
                          {"target", {{"node", static_cast<int>(m)}, {"path", "weights"}}}});
    }
  }
  while (b.bin.size() % 4) b.bin.push_back('\0');
  json doc = {{"asset", {{"version", "2.0"}, {"generator", "layers export --format glb"}}},
              {"scene", 0},
              {"scenes", json::array({{{"nodes",
                                        [&] {
                                          json n = json::array();
                                          for (std::size_t m = 0; m < meshes.size(); ++m) n.push_back(m);
                                          return n;
                                        }()}}})},
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
