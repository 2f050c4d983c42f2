// layers/data/shard_writer.h -- writing one shard file (many sequences).
//
// The shard is built under a temporary name next to the target
// (<name>.tmp-<pid>-<n>) and renamed onto it by commit(): a reader sees the
// old file or the complete new one, never a half-written shard. A writer
// destroyed without commit() (an exception while writing, a rejected
// sequence) removes its temporary file and leaves any previous file intact.
// The shard records the content hash of each sequence it was given (root
// attribute content_hashes), so a shard file read on its own is verified
// too.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "layers/data/sequence.h"

namespace layers::data {

class ShardWriter {
 public:
  explicit ShardWriter(std::string path);
  ~ShardWriter();
  ShardWriter(const ShardWriter&) = delete;
  ShardWriter& operator=(const ShardWriter&) = delete;

  // Checks `seq` (check_sequence) and writes it as /seq/<id>. Throws
  // InputError for a bad or duplicate sequence (nothing of it is written
  // and the writer stays usable); if writing itself fails, the writer
  // refuses further use and commit().
  void append(const SequenceData& seq);
  std::size_t size() const;
  const std::vector<std::string>& ids() const;
  const std::string& path() const;
  // Closes the file and renames it into place.
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes `sequences` as one shard at `path` (atomically).
void write_shard(const std::string& path, const std::vector<SequenceData>& sequences);

}  // namespace layers::data
