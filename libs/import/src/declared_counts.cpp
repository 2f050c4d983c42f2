// Declared counts against the file's size (see declared_counts.h).
#include "declared_counts.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "file_names.h"
#include "layers/core/error.h"

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

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t least = 0;  // the fewest bytes one element takes
};

void check_ply(const std::string& path, std::uint64_t size) {
  std::ifstream in(path, std::ios::binary);
  std::string line, format;
  std::vector<PlyElement> elements;
  std::uint64_t header = 0;
  bool ended = false;
  // A header is a few hundred bytes; 64 KiB without end_header is not one
  // this check understands, and assimp says what it finds.
  while (header < (64u << 10) && std::getline(in, line)) {
    header += line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format") {
      words >> format;
    } else if (key == "element") {
      PlyElement e;
      std::string count;
      words >> e.name >> count;
      if (count.empty() || count.find_first_not_of("0123456789") != std::string::npos || count.size() > 19) return;
      e.count = std::stoull(count);
      elements.push_back(e);
    } else if (key == "property" && !elements.empty()) {
      std::string type;
      words >> type;
      const bool ascii = format == "ascii";
      if (type == "list") {
        std::string count_type;
        words >> count_type;
        // An empty list: its count alone (a digit and a separator in text).
        elements.back().least += ascii ? 2 : ply_type_size(count_type);
      } else {
        elements.back().least += ascii ? 2 : ply_type_size(type);
      }
    } else if (key == "end_header") {
      ended = true;
      break;
    }
  }
  if (!ended) return;
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

}  // namespace

void check_declared_counts(const std::string& path) {
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return;  // assimp says why it cannot read it
  const std::string ext = lower_extension(path);
  if (ext == ".ply") check_ply(path, size);
  if (ext == ".stl") check_stl(path, size);
}

}  // namespace layers::import::detail
