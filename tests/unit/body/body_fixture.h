// body_fixture.h -- shared helpers for the layers::body tests: the body
// model (loaded once per process from the shared assets) and a few bodies.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <string>

#include "layers/body/assets.h"
#include "layers/body/body_model.h"

namespace layers::body::test {

inline std::shared_ptr<const BodyModel> model() { return BodyModel::load(); }

// Bodies are cached by shape so that tests in one process share them.
inline const Body& body(const ShapeParams& s = {}) {
  static std::map<std::array<double, 4>, Body> cache;
  const std::array<double, 4> key{s.gender, s.muscle, s.weight, s.height};
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, model()->build(s)).first;
  return it->second;
}

inline ShapeParams shape(double gender, double muscle, double weight, double height) {
  ShapeParams s;
  s.gender = gender;
  s.muscle = muscle;
  s.weight = weight;
  s.height = height;
  return s;
}

inline std::string clip_path(const std::string& name) { return motion_asset_dir("") + "/" + name; }

}  // namespace layers::body::test
