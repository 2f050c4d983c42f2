// tests/python/write_fixture.cpp -- `layers_python_fixture <folder>`: writes
// the regression fixture (tests/regression/synthetic_fixture.h) into
// <folder>/fixture and prints what the C++ reader reads of it as JSON: the
// ids, the splits, and the content hash (core/checksum.h, FNV-1a 64) of
// every array of every sequence, which the Python tests compare with their
// own reads; and the first and last windows the C++ training loader reads
// in epoch 0 (train split, history 1, horizon 3, seed 7) with the hashes of
// their frames, which layers.WindowDataset must give as its first and last
// items.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "layers/core/checksum.h"
#include "layers/data/dataset.h"
#include "layers/train/window_loader.h"
#include "synthetic_fixture.h"

namespace {

template <typename T>
std::string hash(const std::vector<T>& v) {
  return layers::ContentHash().add(v.data(), v.size() * sizeof(T)).hex();
}

std::string hash(const at::Tensor& t) {
  const at::Tensor c = t.contiguous();
  return layers::ContentHash().add(c.data_ptr(), static_cast<std::size_t>(c.numel()) * c.element_size()).hex();
}

nlohmann::json window_json(const layers::train::Sample& s) {
  nlohmann::json garments = nlohmann::json::array();
  for (const at::Tensor& g : s.frames.garments) garments.push_back(hash(g));
  return {{"id", s.id}, {"start", s.start}, {"body", hash(s.frames.body)}, {"garments", garments}};
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
    layers::train::LoaderOptions options;
    options.split = "train";
    options.history = 1;
    options.batch_size = 2;
    options.seed = 7;
    layers::train::WindowLoader loader(ds, options);
    loader.start_epoch(0, 3);
    std::vector<layers::train::Sample> samples;
    while (auto batch = loader.next())
      for (layers::train::Sample& s : *batch) samples.push_back(std::move(s));
    out["loader"] = {{"split", "train"},
                     {"history", 1},
                     {"horizon", 3},
                     {"seed", 7},
                     {"epoch", 0},
                     {"count", samples.size()},
                     {"first", window_json(samples.front())},
                     {"last", window_json(samples.back())}};
    std::printf("%s\n", out.dump().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "layers_python_fixture: %s\n", e.what());
    return 1;
  }
  return 0;
}
