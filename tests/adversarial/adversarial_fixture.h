// tests/adversarial/adversarial_fixture.h -- what the adversarial tests
// share: a small dataset of two shards (six fixture sequences; train, val
// and test splits; stats.h5) and a snapshot of a folder's files, to show
// that a refused command changed nothing on disk.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "file_bytes.h"
#include "layers/data/dataset.h"
#include "layers/data/dataset_writer.h"
#include "layers/data/stats.h"
#include "synthetic_fixture.h"

namespace layers::test {

// Two shards (seq0-seq2: train; seq3: val; seq4, seq5: test), so that
// sequences can be swapped between shards.
inline std::string write_two_shards(const std::string& dir) {
  data::DatasetWriterOptions options;
  options.sequences_per_shard = 3;
  data::DatasetWriter writer(dir, options);
  for (int s = 0; s < 6; ++s)
    writer.add(regression::detail::fixture_sequence("seq" + std::to_string(s), static_cast<std::uint64_t>(s + 1)));
  writer.set_split("train", {"seq0", "seq1", "seq2"});
  writer.set_split("val", {"seq3"});
  writer.set_split("test", {"seq4", "seq5"});
  writer.finish();
  data::write_dataset_stats(dir, data::compute_stats(data::Dataset::open(dir)));
  return dir;
}

// Every regular file under `dir` (relative path -> bytes); empty when the
// folder does not exist.
inline std::map<std::string, std::string> snapshot(const std::string& dir) {
  std::map<std::string, std::string> out;
  if (!std::filesystem::exists(dir)) return out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file())
      out[std::filesystem::relative(e.path(), dir).string()] = test::read_bytes(e.path().string());
  return out;
}

}  // namespace layers::test
