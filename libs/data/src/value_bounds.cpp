// Physical bounds of the frames a reader returns (see value_bounds.h).
#include "layers/data/value_bounds.h"

#include <cmath>
#include <cstdio>

#include "layers/core/error.h"

namespace layers::data {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

struct Checker {
  const Window& w;
  std::int64_t first, n;  // the window holds frames first .. first + n - 1
  const SequenceInfo& info;
  const std::string& file;

  [[noreturn]] void fail(const std::string& array, const std::string& expected, const std::string& got,
                         std::int64_t frame, const std::string& item) const {
    throw InputError(file, "/seq/" + info.id + "/" + array, expected,
                     got + " at frame " + std::to_string(first + frame) + (item.empty() ? "" : ", " + item));
  }

  const float* root(std::int64_t t) const { return &w.body.root[3 * t]; }

  // [n, count, stride] values, all finite, whose elements x, y, z (a
  // position) lie within kMaxDistanceFromRoot of the frame's root.
  void points(const std::string& array, const std::vector<float>& values, std::int64_t count, int stride, int x, int y,
              int z, const char* item) const {
    if (n <= 0 || count <= 0) return;
    for (std::int64_t t = 0; t < n; ++t) {
      const float* r = root(t);
      for (std::int64_t i = 0; i < count; ++i) {
        const float* p = &values[(t * count + i) * stride];
        for (int c = 0; c < stride; ++c)
          if (!std::isfinite(p[c]))
            fail(array, "finite values", number(p[c]), t, std::string(item) + " " + std::to_string(i));
        const double dx = p[x] - r[0], dy = p[y] - r[1], dz = p[z] - r[2];
        const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (d > kMaxDistanceFromRoot)
          fail(array, "positions within " + number(kMaxDistanceFromRoot) + " m of the body root", number(d) + " m away",
               t, std::string(item) + " " + std::to_string(i));
      }
    }
  }

  void run() const {
    for (std::int64_t t = 0; t < n; ++t) {
      const float* r = root(t);
      for (int c = 0; c < 3; ++c)
        if (!std::isfinite(r[c]) || std::fabs(r[c]) > kMaxRootDistance)
          fail("body/root", "finite values within " + number(kMaxRootDistance) + " m of the origin", number(r[c]), t,
               "");
      for (int c = 0; c < 4; ++c)
        if (!std::isfinite(w.body.root_rot[4 * t + c]))
          fail("body/root_rot", "finite values", number(w.body.root_rot[4 * t + c]), t, "");
      const float* rot = &w.wind.rotation[4 * t];
      for (int c = 0; c < 4; ++c)
        if (!std::isfinite(rot[c])) fail("wind/rotation", "finite values", number(rot[c]), t, "");
      const float s = w.wind.strength[t];
      if (!(s >= 0 && s <= kMaxWindStrength))
        fail("wind/strength", "a strength in [0, " + number(kMaxWindStrength) + "]", number(s), t, "");
    }
    const std::int64_t vb = n > 0 ? static_cast<std::int64_t>(w.body.positions.size()) / (3 * n) : 0;
    points("body/positions", w.body.positions, vb, 3, 0, 1, 2, "vertex");
    const std::int64_t joints = n > 0 ? static_cast<std::int64_t>(w.body.joints.size()) / (12 * n) : 0;
    points("body/joints", w.body.joints, joints, 12, 3, 7, 11, "joint");  // [R | p] row-major: p = column 3
    for (std::size_t g = 0; g < w.garments.size(); ++g) {
      const std::int64_t vg = n > 0 ? static_cast<std::int64_t>(w.garments[g].size()) / (3 * n) : 0;
      const std::string group = g < info.garments.size() ? info.garments[g].group : std::to_string(g);
      points("garments/" + group + "/positions", w.garments[g], vg, 3, 0, 1, 2, "vertex");
    }
  }
};

}  // namespace

void check_frame_values(const Window& window, std::int64_t first, std::int64_t count, const SequenceInfo& info,
                        const std::string& file) {
  Checker{window, first, count, info, file}.run();
}

}  // namespace layers::data
