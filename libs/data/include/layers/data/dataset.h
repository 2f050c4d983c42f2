// layers/data/dataset.h -- the streaming reader.
//
// Dataset::open reads dataset.yaml and splits.yaml and builds an index
// (sequence id -> shard, sizes, attributes) from group names, attributes
// and dataset shapes only: no array is read until asked for. Static
// per-sequence data sits in an LRU cache bounded by cache_bytes; per-frame
// data is read with HDF5 hyperslabs, never whole arrays; at most
// max_open_files shard files are open, each with a small chunk and
// metadata cache, so memory stays bounded whatever the dataset's size.
// All HDF5 calls are serialised by one process-wide mutex, so a Dataset
// may be shared by threads (the returned data is theirs to process in
// parallel). A single shard file can be opened directly (no splits).
//
// Integrity (integrity.h): open() checks the shard set, the counts, the
// splits and the recorded content hashes against the shards, and a
// sequence's content hash is verified when it is first read, before any of
// its values are returned; so damage shows as an InputError, never as
// changed values. A dataset without recorded hashes is refused unless
// allow_unhashed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "layers/data/manifest.h"
#include "layers/data/sequence.h"
#include "layers/data/splits.h"

namespace layers::data {

struct ReaderOptions {
  std::size_t cache_bytes = 64u << 20;       // statics LRU cache
  std::size_t max_open_files = 4;            // shard handles kept open
  std::size_t chunk_cache_bytes = 1u << 20;  // HDF5 raw chunk cache per open dataset
  // Read a dataset (or some of its sequences) without recorded content
  // hashes, unverified; those it has are still verified.
  bool allow_unhashed = false;
};

struct CacheStats {
  std::size_t bytes = 0, entries = 0, hits = 0, misses = 0, open_files = 0;
};

class Dataset {
 public:
  // A dataset folder or a single shard .h5 file. Throws InputError for a
  // missing or malformed dataset.yaml / splits.yaml, a shard that cannot
  // be opened or does not follow the format's structure, duplicate ids
  // across shards, or a split naming an unknown sequence.
  static Dataset open(const std::string& path, ReaderOptions options = {});
  Dataset(Dataset&&) noexcept;
  Dataset& operator=(Dataset&&) noexcept;
  ~Dataset();

  const std::string& path() const;
  const ReaderOptions& options() const;
  const DatasetManifest& manifest() const;  // from dataset.yaml (name only for a single shard)
  const Splits& splits() const;
  std::vector<std::string> ids() const;  // shard order, then order in the shard
  bool contains(const std::string& id) const;
  const SequenceInfo& info(const std::string& id) const;

  // Static data of a sequence, cached. Every read below verifies the
  // sequence's content hash first if it was not verified yet. The pointer stays valid after
  // eviction.
  std::shared_ptr<const SequenceStatic> statics(const std::string& id) const;
  // Frames [start - history, start + horizon] (history + horizon + 1 frames).
  Window read_window(const std::string& id, std::int64_t start, std::int64_t history, std::int64_t horizon) const;
  // Frames [first, first + count).
  Window read_frames(const std::string& id, std::int64_t first, std::int64_t count) const;
  // Everything of one sequence (export, validation, tests).
  SequenceData read_sequence(const std::string& id) const;

  // Verifies the content hash of each of `ids` not verified yet (each read
  // in full once): for a caller that must know before it writes anything.
  void verify(const std::vector<std::string>& ids) const;

  CacheStats cache_stats() const;

 private:
  struct Impl;
  explicit Dataset(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace layers::data
