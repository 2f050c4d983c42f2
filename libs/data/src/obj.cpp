// Wavefront OBJ reading and writing (see obj.h).
#include "layers/data/obj.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "sequence_rules.h"

namespace layers::data {
namespace {

void check_mesh(const std::string& path, const ObjMesh& mesh) {
  if (mesh.positions.size() % 3 != 0) {
    throw InputError(path, "positions", "a multiple of 3 floats ([V,3])", std::to_string(mesh.positions.size()));
  }
  if (mesh.faces.size() % 3 != 0) throw InputError(path, "faces", "a multiple of 3 indices ([F,3])", std::to_string(mesh.faces.size()));
  if (mesh.uv.size() % 2 != 0) throw InputError(path, "uv", "a multiple of 2 floats ([U,2])", std::to_string(mesh.uv.size()));
  if (!mesh.uv_faces.empty() && mesh.uv_faces.size() != mesh.faces.size()) {
    throw InputError(path, "uv_faces", std::to_string(mesh.faces.size()) + " indices (one per face corner)",
                     std::to_string(mesh.uv_faces.size()));
  }
  if (auto problem = check_index_range(mesh.faces, 0, mesh.n_vertices(), 3)) throw InputError::message(path, "faces", *problem);
  if (auto problem = check_index_range(mesh.uv_faces, 0, static_cast<std::int64_t>(mesh.uv.size() / 2), 3)) {
    throw InputError::message(path, "uv_faces", *problem);
  }
}

[[noreturn]] void fail(const std::string& path, int line, const std::string& message) {
  throw InputError::message(path + ":" + std::to_string(line), "", message);
}

bool parse_float(const std::string& token, float& out) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtof(token.c_str(), &end);
  return end == token.c_str() + token.size() && errno != ERANGE;
}

bool parse_index(const std::string& token, long& out) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtol(token.c_str(), &end, 10);
  return end == token.c_str() + token.size() && errno != ERANGE;
}

// Reads `count` required floats (and ignores optional extra ones up to
// `max_count`) after a keyword.
void read_floats(std::istringstream& in, const std::string& path, int line, const char* keyword, std::size_t count,
                 std::size_t max_count, std::vector<float>& out) {
  std::string token;
  std::size_t n = 0;
  while (in >> token) {
    float value = 0.0f;
    if (!parse_float(token, value)) fail(path, line, std::string("expected a number after '") + keyword + "', got '" + token + "'");
    if (n < count) out.push_back(value);
    ++n;
  }
  if (n < count || n > max_count) {
    fail(path, line, std::string("expected ") + std::to_string(count) + " numbers after '" + keyword + "', got " +
                         std::to_string(n));
  }
}

// One face corner "v", "v/vt", "v//vn" or "v/vt/vn" as 0-based indices
// (vt = -1 when absent); negative indices count back from the last element.
struct Corner {
  long v = 0, vt = -1;
};

long resolve(long index, std::size_t count, const std::string& path, int line, const std::string& token) {
  if (index == 0) fail(path, line, "expected a non-zero index in '" + token + "', got 0 (OBJ indices start at 1)");
  const long resolved = index > 0 ? index - 1 : static_cast<long>(count) + index;
  if (resolved < 0) fail(path, line, "index " + std::to_string(index) + " in '" + token + "' points before the first element");
  return resolved;
}

Corner parse_corner(const std::string& token, std::size_t n_v, std::size_t n_vt, const std::string& path, int line) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = token.find('/', start);
    parts.push_back(token.substr(start, slash == std::string::npos ? std::string::npos : slash - start));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  long v = 0, vt = 0, vn = 0;
  const bool ok = parts.size() <= 3 && parse_index(parts[0], v) && (parts.size() < 2 || parts[1].empty() || parse_index(parts[1], vt)) &&
                  (parts.size() < 3 || parse_index(parts[2], vn));
  if (!ok) fail(path, line, "expected a face vertex v, v/vt, v//vn or v/vt/vn, got '" + token + "'");
  Corner c;
  c.v = resolve(v, n_v, path, line, token);
  if (parts.size() >= 2 && !parts[1].empty()) c.vt = resolve(vt, n_vt, path, line, token);
  return c;
}

std::string format_float(float v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", static_cast<double>(v));
  return buffer;
}

}  // namespace

void write_obj(const std::string& path, const ObjMesh& mesh) {
  check_mesh(path, mesh);
  std::string text = "# layers OBJ export\n";
  text.reserve(mesh.positions.size() * 14 + mesh.faces.size() * 12);
  for (std::size_t i = 0; i + 2 < mesh.positions.size(); i += 3) {
    text += "v " + format_float(mesh.positions[i]) + " " + format_float(mesh.positions[i + 1]) + " " +
            format_float(mesh.positions[i + 2]) + "\n";
  }
  for (std::size_t i = 0; i + 1 < mesh.uv.size(); i += 2) {
    text += "vt " + format_float(mesh.uv[i]) + " " + format_float(mesh.uv[i + 1]) + "\n";
  }
  const bool with_uv = !mesh.uv_faces.empty();
  for (std::size_t f = 0; f < mesh.faces.size(); f += 3) {
    text += "f";
    for (std::size_t c = 0; c < 3; ++c) {
      text += " " + std::to_string(mesh.faces[f + c] + 1);
      if (with_uv) text += "/" + std::to_string(mesh.uv_faces[f + c] + 1);
    }
    text += "\n";
  }
  write_text_atomic(path, text);
}

void write_obj(const std::string& path, const std::vector<float>& positions, const std::vector<std::int32_t>& faces,
               const std::vector<float>& uv, const std::vector<std::int32_t>& uv_faces) {
  write_obj(path, ObjMesh{positions, faces, uv, uv_faces});
}

ObjMesh read_obj(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError::message(path, "", "cannot open the file (missing?)");
  ObjMesh mesh;
  std::vector<int> face_lines;  // line of each triangle, for range errors
  int first_with_uv = 0, first_without_uv = 0;
  std::string raw;
  int line = 0;
  while (std::getline(file, raw)) {
    ++line;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    std::istringstream in(raw);
    std::string keyword;
    if (!(in >> keyword) || keyword[0] == '#') continue;
    if (keyword == "v") {
      read_floats(in, path, line, "v", 3, 7, mesh.positions);  // x y z [w] or x y z r g b
    } else if (keyword == "vt") {
      read_floats(in, path, line, "vt", 2, 3, mesh.uv);
    } else if (keyword == "f") {
      std::vector<Corner> corners;
      std::string token;
      while (in >> token) {
        corners.push_back(parse_corner(token, mesh.positions.size() / 3, mesh.uv.size() / 2, path, line));
      }
      if (corners.size() < 3) fail(path, line, "expected a face of at least 3 vertices, got " + std::to_string(corners.size()));
      std::size_t with_uv = 0;
      for (const auto& c : corners) with_uv += c.vt >= 0;
      if (with_uv != 0 && with_uv != corners.size()) fail(path, line, "expected texture coordinates on all or none of the face's vertices");
      int& first = with_uv ? first_with_uv : first_without_uv;
      if (first == 0) first = line;
      for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
        for (const Corner* c : {&corners[0], &corners[i], &corners[i + 1]}) {
          mesh.faces.push_back(static_cast<std::int32_t>(c->v));
          if (with_uv) mesh.uv_faces.push_back(static_cast<std::int32_t>(c->vt));
        }
        face_lines.push_back(line);
      }
    }
    // vn, o, g, s, usemtl, mtllib, l and unknown keywords: nothing to keep.
  }
  if (first_with_uv && first_without_uv) {
    fail(path, std::max(first_with_uv, first_without_uv),
         "expected texture coordinates on every face or on none; faces with them start at line " +
             std::to_string(first_with_uv) + ", faces without at line " + std::to_string(first_without_uv));
  }
  const auto n_v = static_cast<std::int32_t>(mesh.positions.size() / 3);
  const auto n_vt = static_cast<std::int32_t>(mesh.uv.size() / 2);
  for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
    if (mesh.faces[i] >= n_v) {
      fail(path, face_lines[i / 3], "vertex index " + std::to_string(mesh.faces[i] + 1) + " out of range (the file has " +
                                        std::to_string(n_v) + " vertices)");
    }
    if (!mesh.uv_faces.empty() && mesh.uv_faces[i] >= n_vt) {
      fail(path, face_lines[i / 3], "texture coordinate index " + std::to_string(mesh.uv_faces[i] + 1) +
                                        " out of range (the file has " + std::to_string(n_vt) + ")");
    }
  }
  return mesh;
}

}  // namespace layers::data
