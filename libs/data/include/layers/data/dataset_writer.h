// layers/data/dataset_writer.h -- writing a dataset folder.
//
// Sequences are appended to the current shard (shard-NNNNN.h5), which is
// committed atomically once it holds `sequences_per_shard` sequences;
// finish() commits the last partial shard and writes dataset.yaml and
// splits.yaml (both atomically). With `resume`, shards already in the
// folder are kept, their ids reported by contains(), and numbering goes
// on after the last one, so an interrupted generator redoes only the
// sequences of its unfinished shard. Statistics (stats.h5) are a separate
// step: see stats.h.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "layers/data/sequence.h"
#include "layers/data/splits.h"

namespace layers::data {

struct DatasetWriterOptions {
  std::string name = "layers";
  std::uint64_t seed = 0;
  std::int64_t sequences_per_shard = 32;
  std::string generator_config_yaml;  // copied into dataset.yaml under `generator`
  bool resume = false;
};

class DatasetWriter {
 public:
  DatasetWriter(std::string folder, DatasetWriterOptions options = {});
  ~DatasetWriter();  // an uncommitted shard is discarded
  DatasetWriter(const DatasetWriter&) = delete;
  DatasetWriter& operator=(const DatasetWriter&) = delete;

  // Whether a sequence with this id is written (or in the current shard).
  bool contains(const std::string& id) const;
  // Appends a sequence; InputError for a bad sequence or a duplicate id.
  void add(const SequenceData& seq);
  // Sets a split (train, val, test or a named subset). finish() writes an
  // empty train split when none was set: every dataset has one.
  void set_split(const std::string& name, std::vector<std::string> ids);
  // Commits the last shard and writes dataset.yaml + splits.yaml. Every
  // split must name written sequences only (InputError otherwise).
  void finish();
  // Ids written so far (including resumed shards), in order.
  std::vector<std::string> ids() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// "shard-00042.h5"
std::string shard_file_name(std::int64_t index);

}  // namespace layers::data
