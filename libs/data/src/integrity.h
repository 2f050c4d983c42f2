// integrity.h (private) -- the integrity check of a dataset, one code for
// every reader: Dataset::open runs the cheap part (shard set, counts,
// splits, recorded hashes against the shards' own) and Dataset verifies a
// sequence's content hash when it first reads it; `layers validate` runs
// the same functions with a sink that collects instead of throwing.
//
// Where the hashes live: dataset.yaml (`content_hashes`, `stats_hash`,
// `shards`) for a folder; the root attribute `content_hashes` (one
// "<id> <hash>" string per sequence, written by ShardWriter) for a shard
// file, which a folder's reader also compares with dataset.yaml.
#pragma once

#include <H5Cpp.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "layers/data/manifest.h"
#include "layers/data/sequence.h"
#include "shard_layout.h"
#include "splits_source.h"

namespace layers::data {

inline constexpr const char* kContentHashesAttr = "content_hashes";

// What the shards hold, summed over their index.
struct ShardTotals {
  std::int64_t sequences = 0, frames = 0, garments = 0;
  void add(const SequenceInfo& info) {
    ++sequences;
    frames += info.n_frames;
    garments += static_cast<std::int64_t>(info.garments.size());
  }
};

// The shard files present against dataset.yaml's list (or, for a dataset
// written before the list, its counts.shards), naming missing and extra
// files.
void check_shard_set(const std::string& manifest_path, const DatasetManifest& manifest,
                     const std::vector<std::string>& shard_paths, ProblemSink& sink);
// counts.sequences, frames and garments against the shards.
void check_counts(const std::string& manifest_path, const DatasetManifest& manifest, const ShardTotals& found,
                  ProblemSink& sink);
// A train split present (statistics come from it); every id known, none
// twice in a split, none in two of train/val/test.
void check_splits(const SplitsSource& source, const std::map<std::string, std::string>& shard_of_id, ProblemSink& sink);

// A shard's own recorded hashes (id -> hash); empty when it has none.
std::map<std::string, std::string> shard_content_hashes(const std::string& path, const H5::H5File& file);
void write_shard_content_hashes(H5::H5File& file, const std::map<std::string, std::string>& hashes);

// The hashes a reader verifies against, and where they are written.
struct RecordedHashes {
  std::string where, key;  // file, and the field ("content_hashes" or the shard attribute)
  std::map<std::string, std::string> hashes;
  // Ids `where` has no hash for, whose shard records one (read with
  // allow_unhashed): id -> that shard, whose hash in `hashes` is verified.
  std::map<std::string, std::string> from_shard;
};
// dataset.yaml's hashes against the ids of the shards and the shards' own
// hashes: every id has one, the shards agree (a sequence moved, renamed or
// swapped between shards shows here before any data is read). Without
// hashes: a problem unless allow_unhashed.
void check_recorded_hashes(const RecordedHashes& recorded, const std::map<std::string, std::string>& shard_of_id,
                           const std::map<std::string, std::map<std::string, std::string>>& shard_hashes,
                           bool allow_unhashed, ProblemSink& sink);
// A sequence as read against its recorded hash (nothing when there is none
// and unhashed reading was allowed).
void check_content(const RecordedHashes& recorded, const SequenceData& seq, ProblemSink& sink);

// stats.h5 of a folder (its values, stats_content_hash) against
// dataset.yaml's stats_hash; InputError if it cannot be read.
void check_stats_hash(const std::string& folder, const DatasetManifest& manifest, bool allow_unhashed,
                      ProblemSink& sink);

}  // namespace layers::data
