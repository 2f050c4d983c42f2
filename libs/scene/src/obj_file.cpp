// Minimal OBJ parsing (see obj_file.h).
#include "obj_file.h"

#include <cstdlib>
#include <fstream>

#include "layers/core/error.h"

namespace layers::scene {

ObjPolygons read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError::message(path, "", "cannot open OBJ file");
  ObjPolygons obj;
  obj.face_start.push_back(0);
  std::string text;
  int line = 0;
  std::vector<int> index_line;  // per index, for errors found after reading
  while (std::getline(in, text)) {
    ++line;
    auto where = [&] { return "line " + std::to_string(line); };
    if (text.size() < 2) continue;
    if (text[0] == 'v' && text[1] == ' ') {
      const char* p = text.c_str() + 2;
      for (int k = 0; k < 3; ++k) {
        char* end = nullptr;
        double x = std::strtod(p, &end);
        if (end == p) throw InputError(path, where(), "'v x y z'", "'" + text + "'");
        obj.positions.push_back(x);
        p = end;
      }
    } else if (text[0] == 'f' && text[1] == ' ') {
      const char* p = text.c_str() + 2;
      int count = 0;
      while (true) {
        while (*p == ' ' || *p == '\t') ++p;
        if (*p == '\0' || *p == '\r') break;
        char* end = nullptr;
        long index = std::strtol(p, &end, 10);
        if (end == p || index == 0) throw InputError(path, where(), "'f i j k ...' with 1-based indices", "'" + text + "'");
        // Relative (negative) indices count back from the vertices read so far.
        long resolved = index > 0 ? index - 1 : obj.num_vertices() + index;
        obj.indices.push_back(static_cast<int>(resolved));
        index_line.push_back(line);
        ++count;
        p = end;
        while (*p != '\0' && *p != ' ' && *p != '\t' && *p != '\r') ++p;  // skip /vt/vn
      }
      if (count < 3) throw InputError(path, where(), "a face with at least 3 vertices", std::to_string(count));
      obj.face_start.push_back(static_cast<int>(obj.indices.size()));
    }
  }
  for (std::size_t i = 0; i < obj.indices.size(); ++i)
    if (obj.indices[i] < 0 || obj.indices[i] >= obj.num_vertices())
      throw InputError(path, "line " + std::to_string(index_line[i]),
                       "a vertex index in [1, " + std::to_string(obj.num_vertices()) + "]",
                       std::to_string(obj.indices[i] + 1));
  return obj;
}

}  // namespace layers::scene
