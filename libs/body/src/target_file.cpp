// Reading gzip-compressed MakeHuman targets with zlib (see target_file.h).
#include "target_file.h"

#include <cstdlib>
#include <memory>

#include <zlib.h>

#include "layers/core/error.h"

namespace layers::body {

ShapeTarget read_target(const std::string& path, int num_vertices) {
  // gzopen reads plain text transparently, so uncompressed targets work too.
  std::unique_ptr<gzFile_s, int (*)(gzFile)> file(gzopen(path.c_str(), "rb"), gzclose);
  if (!file) throw InputError::message(path, "", "cannot open shape target");
  ShapeTarget target;
  char buffer[512];
  int line = 0;
  while (gzgets(file.get(), buffer, sizeof buffer)) {
    ++line;
    const char* p = buffer;
    while (*p == ' ' || *p == '\t') ++p;
    if (*p == '#' || *p == '\n' || *p == '\r' || *p == '\0') continue;
    char* end = nullptr;
    long index = std::strtol(p, &end, 10);
    float d[3];
    bool ok = end != p;
    for (int k = 0; k < 3 && ok; ++k) {
      p = end;
      d[k] = std::strtof(p, &end);
      ok = end != p;
    }
    if (!ok)
      throw InputError(path, "line " + std::to_string(line), "'vertex dx dy dz'", std::string("'") + buffer + "'");
    if (index < 0 || index >= num_vertices)
      throw InputError(path, "line " + std::to_string(line),
                       "a vertex index in [0, " + std::to_string(num_vertices) + ")", std::to_string(index));
    target.vertex.push_back(static_cast<int>(index));
    target.offset.insert(target.offset.end(), d, d + 3);
  }
  int err = 0;
  gzerror(file.get(), &err);
  if (err != Z_OK && err != Z_STREAM_END) throw InputError::message(path, "", "corrupt gzip stream");
  return target;
}

}  // namespace layers::body
