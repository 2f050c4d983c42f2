// Wavefront OBJ reading (see obj.h).
#include "layers/geometry/obj.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "layers/core/error.h"

namespace layers::geometry {
namespace {

[[noreturn]] void fail(const std::string& path, int line, const std::string& message) {
  throw InputError::message(path + ":" + std::to_string(line), "", message);
}

bool parse_number(const std::string& token, double& out) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && errno != ERANGE;
}

bool parse_index(const std::string& token, long& out) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtol(token.c_str(), &end, 10);
  return end == token.c_str() + token.size() && errno != ERANGE;
}

// Reads `count` required numbers (and ignores optional extra ones up to
// `max_count`) after a keyword.
void read_numbers(std::istringstream& in, const std::string& path, int line, const char* keyword, std::size_t count,
                  std::size_t max_count, std::vector<double>& out) {
  std::string token;
  std::size_t n = 0;
  while (in >> token) {
    double value = 0.0;
    if (!parse_number(token, value))
      fail(path, line, std::string("expected a number after '") + keyword + "', got '" + token + "'");
    if (n < count) out.push_back(value);
    ++n;
  }
  if (n < count || n > max_count) {
    fail(path, line,
         std::string("expected ") + std::to_string(count) + " numbers after '" + keyword + "', got " +
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
  if (resolved < 0)
    fail(path, line, "index " + std::to_string(index) + " in '" + token + "' points before the first element");
  // Indices are kept as int: larger ones cannot name an element of any
  // file this reads (and would wrap onto another vertex).
  if (resolved >= std::numeric_limits<int>::max())
    fail(path, line,
         "expected an index of at most " + std::to_string(std::numeric_limits<int>::max() - 1) + " in '" + token +
             "', got " + std::to_string(index));
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
  const bool ok = parts.size() <= 3 && parse_index(parts[0], v) &&
                  (parts.size() < 2 || parts[1].empty() || parse_index(parts[1], vt)) &&
                  (parts.size() < 3 || parse_index(parts[2], vn));
  if (!ok) fail(path, line, "expected a face vertex v, v/vt, v//vn or v/vt/vn, got '" + token + "'");
  Corner c;
  c.v = resolve(v, n_v, path, line, token);
  if (parts.size() >= 2 && !parts[1].empty()) c.vt = resolve(vt, n_vt, path, line, token);
  return c;
}

}  // namespace

ObjPolygons read_obj_polygons(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError::message(path, "", "cannot open the file (missing?)");
  ObjPolygons obj;
  obj.face_start.push_back(0);
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
      read_numbers(in, path, line, "v", 3, 7, obj.positions);  // x y z [w] or x y z r g b
    } else if (keyword == "vt") {
      read_numbers(in, path, line, "vt", 2, 3, obj.uv);
    } else if (keyword == "f") {
      std::vector<Corner> corners;
      std::string token;
      while (in >> token)
        corners.push_back(parse_corner(token, obj.positions.size() / 3, obj.uv.size() / 2, path, line));
      if (corners.size() < 3)
        fail(path, line, "expected a face of at least 3 vertices, got " + std::to_string(corners.size()));
      std::size_t with_uv = 0;
      for (const auto& c : corners) with_uv += c.vt >= 0;
      if (with_uv != 0 && with_uv != corners.size())
        fail(path, line, "expected texture coordinates on all or none of the face's vertices");
      int& first = with_uv ? first_with_uv : first_without_uv;
      if (first == 0) first = line;
      for (const Corner& c : corners) {
        obj.indices.push_back(static_cast<int>(c.v));
        if (with_uv) obj.uv_indices.push_back(static_cast<int>(c.vt));
      }
      obj.face_start.push_back(static_cast<int>(obj.indices.size()));
      obj.face_line.push_back(line);
    }
    // vn, o, g, s, usemtl, mtllib, l and unknown keywords: nothing to keep.
  }
  if (first_with_uv && first_without_uv) {
    fail(path, std::max(first_with_uv, first_without_uv),
         "expected texture coordinates on every face or on none; faces with them start at line " +
             std::to_string(first_with_uv) + ", faces without at line " + std::to_string(first_without_uv));
  }
  const int n_v = obj.num_vertices();
  const int n_vt = static_cast<int>(obj.uv.size() / 2);
  for (int f = 0; f < obj.num_faces(); ++f) {
    for (int i = obj.face_start[f]; i < obj.face_start[f + 1]; ++i) {
      if (obj.indices[i] >= n_v) {
        fail(path, obj.face_line[f],
             "vertex index " + std::to_string(obj.indices[i] + 1) + " out of range (the file has " +
                 std::to_string(n_v) + " vertices)");
      }
      if (!obj.uv_indices.empty() && obj.uv_indices[i] >= n_vt) {
        fail(path, obj.face_line[f],
             "texture coordinate index " + std::to_string(obj.uv_indices[i] + 1) + " out of range (the file has " +
                 std::to_string(n_vt) + ")");
      }
    }
  }
  return obj;
}

}  // namespace layers::geometry
