// Sequence content hashes (see content_hash.h).
#include "layers/data/content_hash.h"

#include <cstdint>
#include <filesystem>

#include "dataset_files.h"
#include "integrity.h"
#include "layers/core/checksum.h"
#include "layers/data/dataset.h"
#include "layers/data/manifest.h"
#include "layers/data/stats.h"

namespace layers::data {
namespace {

// Each value is preceded by its size, so that no two contents hash the
// same bytes.
struct Hasher {
  ContentHash h;
  void size(std::size_t n) {
    const auto v = static_cast<std::uint64_t>(n);
    h.add(&v, sizeof v);
  }
  void text(const std::string& s) {
    size(s.size());
    h.add(s);
  }
  template <class T>
  void values(const std::vector<T>& v) {
    size(v.size());
    if (!v.empty()) h.add(v.data(), v.size() * sizeof(T));
  }
  void number(double v) { h.add(&v, sizeof v); }
  void integer(std::int64_t v) { h.add(&v, sizeof v); }
  void texts(const std::vector<std::string>& v) {
    size(v.size());
    for (const auto& s : v) text(s);
  }
  void numbers(const std::map<std::string, double>& m) {
    size(m.size());
    for (const auto& [k, v] : m) {
      text(k);
      number(v);
    }
  }
};

}  // namespace

std::string sequence_content_hash(const SequenceData& seq) {
  Hasher x;
  x.integer(seq.n_frames);
  x.text(seq.motion);
  x.integer(static_cast<std::int64_t>(seq.seed));
  x.texts(seq.tags);
  x.numbers(seq.shape);
  const BodyData& b = seq.body;
  x.values(b.faces);
  x.texts(b.joint_names);
  x.values(b.joint_parents);
  x.values(b.skin_index);
  x.values(b.skin_weight);
  x.values(b.tpose_joints);
  x.values(b.positions);
  x.values(b.root);
  x.values(b.root_rot);
  x.values(b.joints);
  x.values(seq.wind.rotation);
  x.values(seq.wind.strength);
  x.size(seq.garments.size());
  for (const GarmentData& g : seq.garments) {
    x.text(g.name);
    x.text(g.type);
    x.integer(g.layer);
    x.numbers(g.attributes);
    x.values(g.faces);
    x.values(g.rest);
    x.values(g.uv);
    x.values(g.uv_faces);
    x.values(g.panel);
    x.values(g.positions);
  }
  return x.h.hex();
}

void record_integrity(const std::string& folder) {
  const std::string manifest_path = (std::filesystem::path(folder) / kManifestFile).string();
  DatasetManifest manifest = read_manifest(manifest_path);
  ReaderOptions options;
  options.allow_unhashed = true;  // those recorded already are verified as they are read
  const Dataset dataset = Dataset::open(folder, options);
  manifest.shards.clear();
  for (const std::string& shard : list_shards(folder))
    manifest.shards.push_back(std::filesystem::path(shard).filename().string());
  for (const std::string& id : dataset.ids())
    manifest.content_hashes[id] = sequence_content_hash(dataset.read_sequence(id));
  const std::string stats = (std::filesystem::path(folder) / kStatsFile).string();
  if (std::filesystem::exists(stats)) manifest.stats_hash = stats_content_hash(read_stats(stats));
  write_manifest(manifest_path, manifest);
}

}  // namespace layers::data
