// Declared counts against the file's size (see declared_counts.h).
#include "declared_counts.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "file_names.h"
#include "layers/core/error.h"

#include <nlohmann/json.hpp>

namespace layers::import::detail {
namespace {

// Bytes of a PLY scalar type (0: unknown).
std::uint64_t ply_type_size(const std::string& t) {
  static const std::map<std::string, std::uint64_t> sizes = {
      {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(t);
  return it == sizes.end() ? 0 : it->second;
}

struct PlyProperty {
  std::string name;
  std::uint64_t size = 0;        // scalar (or list item) bytes
  std::uint64_t count_size = 0;  // a list's count bytes (0: a scalar)
  bool is_float = false;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t least = 0;  // the fewest bytes one element takes
  std::vector<PlyProperty> properties;
};

[[noreturn]] void ply_fail(const std::string& path, const std::string& where, const std::string& expected,
                           const std::string& got) {
  throw InputError(path, where, expected, got);
}

// An unsigned or signed integer of `size` bytes at p (little- or big-endian).
std::int64_t ply_integer(const unsigned char* p, std::uint64_t size, bool big, bool is_signed) {
  std::uint64_t v = 0;
  for (std::uint64_t k = 0; k < size; ++k) v |= static_cast<std::uint64_t>(p[big ? size - 1 - k : k]) << (8 * k);
  if (is_signed && size < 8 && (v >> (8 * size - 1)) & 1) v |= ~0ull << (8 * size);
  return static_cast<std::int64_t>(v);
}

// Every element's rows against the header: the data's length (binary) or
// token counts (text), list counts, and the faces' vertex indices within
// the vertices. assimp 5.2's PLY reader and its post-processing crashed
// on files that break these (the importer fuzzer).
void check_ply_data(const std::string& path, std::ifstream& in, const std::string& format,
                    const std::vector<PlyElement>& elements, std::uint64_t size, std::uint64_t header) {
  std::uint64_t vertices = 0;
  for (const PlyElement& e : elements)
    if (e.name == "vertex") vertices = e.count;
  const auto is_index = [](const PlyElement& e, const PlyProperty& p) {
    return e.name == "face" && p.count_size > 0 && (p.name == "vertex_indices" || p.name == "vertex_index");
  };
  const auto bad_index = [&](const PlyElement& e, std::uint64_t row, std::int64_t index) {
    ply_fail(path, "element " + e.name + " " + std::to_string(row),
             "vertex indices from 0 to " + std::to_string(vertices == 0 ? 0 : vertices - 1), std::to_string(index));
  };
  if (format == "ascii") {
    std::string token;
    for (const PlyElement& e : elements)
      for (std::uint64_t row = 0; row < e.count; ++row) {
        std::string line;
        do {
          if (!std::getline(in, line))
            ply_fail(path, "element " + e.name, std::to_string(e.count) + " rows", std::to_string(row));
        } while (line.find_first_not_of(" \t\r") == std::string::npos);
        std::istringstream words(line);
        for (const PlyProperty& p : e.properties) {
          std::uint64_t n = 1;
          if (p.count_size > 0) {
            if (!(words >> token) || token.find_first_not_of("0123456789") != std::string::npos || token.size() > 9)
              ply_fail(path, "element " + e.name + " " + std::to_string(row), "a list count", "'" + token + "'");
            n = std::stoull(token);
            if (is_index(e, p) && n < 3)
              ply_fail(path, "element " + e.name + " " + std::to_string(row), "a face of 3 or more vertices",
                       std::to_string(n));
          }
          for (std::uint64_t k = 0; k < n; ++k) {
            if (!(words >> token))
              ply_fail(path, "element " + e.name + " " + std::to_string(row), "a value of " + p.name,
                       "the end of the line");
            char* stop = nullptr;
            const double v = std::strtod(token.c_str(), &stop);
            if (stop == token.c_str() || *stop != '\0' || !std::isfinite(v))
              ply_fail(path, "element " + e.name + " " + std::to_string(row), "a number", "'" + token + "'");
            if (is_index(e, p) && (v < 0 || v >= static_cast<double>(vertices) || v != std::floor(v)))
              bad_index(e, row, static_cast<std::int64_t>(v));
          }
        }
      }
    return;
  }
  const bool big = format == "binary_big_endian";
  std::uint64_t at = header;
  std::vector<unsigned char> buf(64);
  for (const PlyElement& e : elements)
    for (std::uint64_t row = 0; row < e.count; ++row)
      for (const PlyProperty& p : e.properties) {
        std::uint64_t n = 1;
        if (p.count_size > 0) {
          if (at + p.count_size > size)
            ply_fail(path, "element " + e.name, "data for " + std::to_string(e.count) + " rows",
                     "the file ends in row " + std::to_string(row));
          in.read(reinterpret_cast<char*>(buf.data()), static_cast<std::streamsize>(p.count_size));
          const std::int64_t c = ply_integer(buf.data(), p.count_size, big, false);
          at += p.count_size;
          if (c < 0 || static_cast<std::uint64_t>(c) > (size - at) / std::max<std::uint64_t>(p.size, 1))
            ply_fail(path, "element " + e.name + " " + std::to_string(row), "a list count within the file",
                     std::to_string(c));
          n = static_cast<std::uint64_t>(c);
          if (is_index(e, p) && n < 3)
            ply_fail(path, "element " + e.name + " " + std::to_string(row), "a face of 3 or more vertices",
                     std::to_string(n));
        }
        if (at + n * p.size > size)
          ply_fail(path, "element " + e.name, "data for " + std::to_string(e.count) + " rows",
                   "the file ends in row " + std::to_string(row));
        for (std::uint64_t k = 0; k < n; ++k) {
          in.read(reinterpret_cast<char*>(buf.data()), static_cast<std::streamsize>(p.size));
          if (is_index(e, p) && !p.is_float) {
            const std::int64_t index = ply_integer(buf.data(), p.size, big, true);
            if (index < 0 || static_cast<std::uint64_t>(index) >= vertices) bad_index(e, row, index);
          }
        }
        at += n * p.size;
      }
}

void check_ply(const std::string& path, std::uint64_t size) {
  std::ifstream in(path, std::ios::binary);
  std::string line, format;
  std::vector<PlyElement> elements;
  std::uint64_t header = 0;
  int number = 0;
  bool ended = false;
  const auto where = [&]() { return "header line " + std::to_string(number); };
  while (header < (64u << 10) && std::getline(in, line)) {
    header += line.size() + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (number == 1) {
      if (key != "ply") ply_fail(path, where(), "'ply'", "'" + key + "'");
      continue;
    }
    if (key == "format") {
      words >> format;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        ply_fail(path, where(), "format ascii, binary_little_endian or binary_big_endian", "'" + format + "'");
    } else if (key == "element") {
      PlyElement e;
      std::string count;
      words >> e.name >> count;
      if (e.name.empty() || count.empty() || count.find_first_not_of("0123456789") != std::string::npos ||
          count.size() > 19)
        ply_fail(path, where(), "element <name> <count>", "'" + line + "'");
      e.count = std::stoull(count);
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) ply_fail(path, where(), "an element before its properties", "'" + line + "'");
      std::string type;
      words >> type;
      const bool ascii = format == "ascii";
      PlyProperty p;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> p.name;
        p.count_size = ply_type_size(count_type);
        p.size = ply_type_size(item_type);
        p.is_float = item_type.find("float") != std::string::npos || item_type == "double";
        if (p.count_size == 0 || p.size == 0 || p.name.empty() || count_type.find("float") != std::string::npos ||
            count_type == "double")
          ply_fail(path, where(), "property list <integer type> <type> <name>", "'" + line + "'");
        // An empty list: its count alone (a digit and a separator in text).
        elements.back().least += ascii ? 2 : p.count_size;
      } else {
        words >> p.name;
        p.size = ply_type_size(type);
        p.is_float = type.find("float") != std::string::npos || type == "double";
        if (p.size == 0 || p.name.empty()) ply_fail(path, where(), "property <type> <name>", "'" + line + "'");
        elements.back().least += ascii ? 2 : p.size;
      }
      elements.back().properties.push_back(p);
    } else if (key == "end_header") {
      ended = true;
      break;
    } else if (key != "comment" && key != "obj_info") {
      ply_fail(path, where(), "ply, format, comment, obj_info, element, property or end_header", "'" + key + "'");
    }
  }
  if (!ended) ply_fail(path, "header", "an end_header line within 64 KiB", "none");
  if (format.empty()) ply_fail(path, "header", "a format line", "none");
  std::uint64_t left = size > header ? size - header : 0;
  for (const PlyElement& e : elements) {
    if (e.least == 0) continue;
    const std::uint64_t most = left / e.least;
    if (e.count > most)
      throw InputError(path, "element " + e.name,
                       "at most " + std::to_string(most) + " (what the " + std::to_string(size) +
                           "-byte file has room for after the elements before it)",
                       "a header declaring " + std::to_string(e.count));
    left -= e.count * e.least;
  }
  check_ply_data(path, in, format, elements, size, header);
}

void check_stl(const std::string& path, std::uint64_t size) {
  std::ifstream in(path, std::ios::binary);
  char head[84] = {};
  in.read(head, sizeof head);
  if (in.gcount() < 84) return;  // too short to be binary: assimp reads it as text or refuses it
  // Text STL starts with "solid" and holds no NUL in its first bytes (a
  // binary header may start with "solid" too).
  if (std::string(head, 5) == "solid") {
    bool text = true;
    for (int k = 0; k < 80 && text; ++k) text = head[k] != '\0';
    if (text) return;
  }
  const auto* b = reinterpret_cast<const unsigned char*>(head + 80);
  const std::uint64_t facets = b[0] | (b[1] << 8) | (b[2] << 16) | (static_cast<std::uint64_t>(b[3]) << 24);
  const std::uint64_t most = (size - 84) / 50;
  if (facets > most)
    throw InputError(path, "facet count",
                     "at most " + std::to_string(most) + " facets (50 bytes each after the 84-byte header of a " +
                         std::to_string(size) + "-byte binary STL)",
                     std::to_string(facets));
}

// An integer field of `o` (`fallback` when absent); InputError naming
// `where` when present and not an integer in [lo, hi].
std::int64_t gltf_int(const std::string& path, const nlohmann::json& o, const char* key, const std::string& where,
                      std::int64_t lo, std::int64_t hi, std::int64_t fallback) {
  if (!o.is_object() || !o.contains(key)) return fallback;
  const nlohmann::json& v = o.at(key);
  if (!v.is_number_integer() || v.get<std::int64_t>() < lo || v.get<std::int64_t>() > hi)
    throw InputError(path, where + "." + key, "an integer from " + std::to_string(lo) + " to " + std::to_string(hi),
                     v.dump().substr(0, 40));
  return v.get<std::int64_t>();
}

// The buffer views and accessors, as the glTF 2.0 specification bounds
// them, before assimp reads them: assimp 5.2 divided by an accessor's
// count of 0 (SIGFPE; the importer fuzzer, a mutated GLB) and reads a view
// past its buffer unchecked.
void check_gltf_accessors(const std::string& path, const nlohmann::json& doc) {
  constexpr std::int64_t kBig = std::int64_t{1} << 40;
  const auto array = [&](const char* key) {
    if (!doc.contains(key)) return nlohmann::json::array();
    if (!doc.at(key).is_array()) throw InputError(path, key, "an array", doc.at(key).type_name());
    return doc.at(key);
  };
  const nlohmann::json buffers = array("buffers"), views = array("bufferViews"), accessors = array("accessors");
  std::vector<std::int64_t> buffer_length;
  for (std::size_t b = 0; b < buffers.size(); ++b)
    buffer_length.push_back(gltf_int(path, buffers[b], "byteLength", "buffers[" + std::to_string(b) + "]", 1, kBig, 0));
  struct View {
    std::int64_t length, stride;
  };
  std::vector<View> view_of;
  for (std::size_t v = 0; v < views.size(); ++v) {
    const std::string where = "bufferViews[" + std::to_string(v) + "]";
    const std::int64_t buffer =
        gltf_int(path, views[v], "buffer", where, 0, static_cast<std::int64_t>(buffers.size()) - 1, -1);
    if (buffer < 0) throw InputError(path, where + ".buffer", "a buffer index", "none");
    const std::int64_t offset = gltf_int(path, views[v], "byteOffset", where, 0, kBig, 0);
    const std::int64_t length = gltf_int(path, views[v], "byteLength", where, 1, kBig, 0);
    if (length < 1) throw InputError(path, where + ".byteLength", "a length of 1 or more", "none");
    if (buffer_length[static_cast<std::size_t>(buffer)] > 0 &&
        offset + length > buffer_length[static_cast<std::size_t>(buffer)])
      throw InputError(
          path, where,
          "a view within its buffer of " + std::to_string(buffer_length[static_cast<std::size_t>(buffer)]) + " bytes",
          "bytes " + std::to_string(offset) + " to " + std::to_string(offset + length));
    view_of.push_back({length, gltf_int(path, views[v], "byteStride", where, 4, 252, 0)});
  }
  static const std::map<std::int64_t, std::int64_t> component = {{5120, 1}, {5121, 1}, {5122, 2},
                                                                 {5123, 2}, {5125, 4}, {5126, 4}};
  static const std::map<std::string, std::int64_t> components = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                                                 {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
  for (std::size_t a = 0; a < accessors.size(); ++a) {
    const nlohmann::json& acc = accessors[a];
    const std::string where = "accessors[" + std::to_string(a) + "]";
    const std::int64_t count = gltf_int(path, acc, "count", where, 1, kBig, 0);
    if (count < 1) throw InputError(path, where + ".count", "a count of 1 or more", "none");
    const std::int64_t type = gltf_int(path, acc, "componentType", where, 0, 1 << 20, 0);
    const std::string kind = acc.is_object() && acc.contains("type") && acc.at("type").is_string()
                                 ? acc.at("type").get<std::string>()
                                 : std::string();
    if (!component.count(type))
      throw InputError(path, where + ".componentType", "5120, 5121, 5122, 5123, 5125 or 5126", std::to_string(type));
    if (!components.count(kind))
      throw InputError(path, where + ".type", "SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4", "'" + kind + "'");
    const std::int64_t view =
        gltf_int(path, acc, "bufferView", where, 0, static_cast<std::int64_t>(views.size()) - 1, -1);
    if (view < 0) continue;  // all zeros (or sparse), nothing read
    const std::int64_t element = component.at(type) * components.at(kind);
    const View& v = view_of[static_cast<std::size_t>(view)];
    const std::int64_t offset = gltf_int(path, acc, "byteOffset", where, 0, kBig, 0);
    const std::int64_t stride = v.stride > 0 ? v.stride : element;
    if (offset + stride * (count - 1) + element > v.length)
      throw InputError(path, where,
                       "its " + std::to_string(count) + " elements within bufferViews[" + std::to_string(view) + "] (" +
                           std::to_string(v.length) + " bytes)",
                       std::to_string(offset + stride * (count - 1) + element) + " bytes");
  }
}

// A glTF's JSON must parse (assimp says only "No suitable reader found"
// when it does not); a GLB's header and JSON chunk must lie in the file.
void check_gltf(const std::string& path, std::uint64_t size, bool binary) {
  std::ifstream in(path, std::ios::binary);
  std::string json_text;
  if (binary) {
    unsigned char head[20] = {};
    in.read(reinterpret_cast<char*>(head), sizeof head);
    if (in.gcount() < 20)
      throw InputError(path, "GLB header", "a 12-byte header and a JSON chunk", std::to_string(size) + " bytes");
    const auto u32 = [&](int at) {
      return static_cast<std::uint64_t>(head[at]) | (static_cast<std::uint64_t>(head[at + 1]) << 8) |
             (static_cast<std::uint64_t>(head[at + 2]) << 16) | (static_cast<std::uint64_t>(head[at + 3]) << 24);
    };
    if (u32(0) != 0x46546C67u) throw InputError(path, "GLB header", "the magic 'glTF'", "other bytes");
    if (u32(4) != 2) throw InputError(path, "GLB header", "glTF version 2", std::to_string(u32(4)));
    if (u32(8) > size)
      throw InputError(path, "GLB header", "a length within the file's " + std::to_string(size) + " bytes",
                       std::to_string(u32(8)));
    if (u32(16) != 0x4E4F534Au) throw InputError(path, "GLB chunk 0", "a JSON chunk first", "another chunk type");
    if (u32(12) > size - 20)
      throw InputError(path, "GLB chunk 0", "a JSON chunk within the file", std::to_string(u32(12)) + " bytes");
    json_text.resize(static_cast<std::size_t>(u32(12)));
    in.read(json_text.data(), static_cast<std::streamsize>(json_text.size()));
  } else {
    std::ostringstream all;
    all << in.rdbuf();
    json_text = all.str();
  }
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path, binary ? "GLB JSON chunk" : "JSON", "valid JSON", e.what());
  }
  if (!doc.is_object()) throw InputError(path, binary ? "GLB JSON chunk" : "JSON", "a JSON object", doc.type_name());
  check_gltf_accessors(path, doc);
}

}  // namespace

void check_declared_counts(const std::string& path) {
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return;  // assimp says why it cannot read it
  const std::string ext = lower_extension(path);
  if (ext == ".ply") check_ply(path, size);
  if (ext == ".stl") check_stl(path, size);
  if (ext == ".glb" || ext == ".gltf") check_gltf(path, size, ext == ".glb");
}

}  // namespace layers::import::detail
