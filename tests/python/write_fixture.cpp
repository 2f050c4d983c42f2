// tests/python/write_fixture.cpp -- `layers_python_fixture <folder>`: writes
// the regression fixture (tests/regression/synthetic_fixture.h) into
// <folder>/fixture and prints what the C++ reader reads of it as JSON: the
// ids, the splits, and the content hash (core/checksum.h, FNV-1a 64) of
// every array of every sequence, which the Python tests compare with their
// own reads.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "layers/core/checksum.h"
#include "layers/data/dataset.h"
#include "synthetic_fixture.h"

namespace {

template <typename T>
std::string hash(const std::vector<T>& v) {
  return layers::ContentHash().add(v.data(), v.size() * sizeof(T)).hex();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: layers_python_fixture <folder>\n");
    return 2;
  }
  try {
    const std::string dir = layers::regression::write_fixture(argv[1]);
    const layers::data::Dataset ds = layers::data::Dataset::open(dir);
    nlohmann::json out = {{"dataset", dir}, {"ids", ds.ids()}};
    for (const std::string& name : ds.splits().names()) out["splits"][name] = ds.splits().get(name);
    for (const std::string& id : ds.ids()) {
      const layers::data::SequenceData s = ds.read_sequence(id);
      nlohmann::json& h = out["hashes"][id];
      h["body/positions"] = hash(s.body.positions);
      h["body/faces"] = hash(s.body.faces);
      h["body/joints"] = hash(s.body.joints);
      h["body/skin_weight"] = hash(s.body.skin_weight);
      h["wind/strength"] = hash(s.wind.strength);
      for (std::size_t g = 0; g < s.garments.size(); ++g) {
        const std::string k = "garments/" + std::to_string(g) + "/";
        h[k + "positions"] = hash(s.garments[g].positions);
        h[k + "rest"] = hash(s.garments[g].rest);
        h[k + "faces"] = hash(s.garments[g].faces);
        h[k + "uv"] = hash(s.garments[g].uv);
      }
    }
    std::printf("%s\n", out.dump().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "layers_python_fixture: %s\n", e.what());
    return 1;
  }
  return 0;
}
