// layers/data/manifest.h -- dataset.yaml: what a dataset folder holds.
//
//   format: layers-h5
//   format_version: 1
//   name: <name>
//   seed: <generator seed>
//   sequences_per_shard: <n>
//   counts: {sequences: n, frames: n, garments: n, shards: n}
//   motions: {distinct: n, families: {<family>: {sequences: n, distinct: n, skipped: n}}}  # optional
//   generator: <the generator config, as a YAML mapping; optional>
//   generator_revision: <source revision of the generator that simulated the scenes; optional>
//   shards: [shard-00000.h5, ...]                            # the shard files; optional (older datasets)
//   content_hashes: {<sequence id>: <16 hex digits>, ...}   # optional (content_hash.h)
//   stats_hash: <16 hex digits>   # content hash of stats.h5's values (stats.h); optional
//
// The readers refuse a dataset whose content hashes or stats hash are
// missing unless opened with allow_unhashed (integrity.h); `layers
// generate --finalize` records them for a dataset written before.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace layers::data {

// How many different motions the sequences play, per family (the first
// word of the `motion` attribute, e.g. procedural:walk); skipped counts the
// scenes of the family the generator rejected.
// Per motion family: sequences written, distinct motions among them,
// scenes skipped; and, where the generator recorded each scene's outcome
// (-1 / empty when not recorded): scenes started, sequences cut to a clean
// window, recorded frames asked for (scenes x frames), simulated and
// stored, and the frames not stored by the rule that cost them.
struct MotionFamilyCount {
  std::int64_t sequences = 0, distinct = 0, skipped = 0;
  std::int64_t scenes = -1, cut = -1, frames_asked = -1, frames_simulated = -1, frames_stored = -1;
  std::map<std::string, std::int64_t> dropped;  // rule -> recorded frames not stored
};

struct DatasetManifest {
  std::string name;
  std::uint64_t seed = 0;
  std::int64_t format_version = 1;
  std::int64_t sequences_per_shard = 0;
  std::int64_t n_sequences = 0, n_frames = 0, n_garments = 0, n_shards = 0;
  std::int64_t n_distinct_motions = -1;                      // -1: not recorded (no motions block)
  std::map<std::string, MotionFamilyCount> motion_families;  // family -> counts
  std::string generator_yaml;                                // YAML text of the generator config; "" if none
  std::string generator_revision;  // source_revision() of the generator that made the scenes; "" if not recorded
  std::map<std::string, std::string> content_hashes;  // id -> content hash; empty if not recorded
  std::vector<std::string> shards;                    // shard file names; empty if not recorded
  std::string stats_hash;                             // stats_content_hash of stats.h5; "" if not recorded
};

std::string manifest_to_yaml(const DatasetManifest& manifest);
// Throws InputError (with file:line) on malformed YAML, missing keys or
// an unsupported format/version.
DatasetManifest read_manifest(const std::string& path);
// Atomic write. Throws InputError if generator_yaml is not valid YAML.
void write_manifest(const std::string& path, const DatasetManifest& manifest);

}  // namespace layers::data
