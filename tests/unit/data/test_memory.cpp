// Bounded memory: a dataset much larger than the reader's cache, read with
// 100 random windows, must not grow the resident set by more than a fixed
// bound. The figures are printed for the record.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "layers/core/memory.h"
#include "layers/core/progress.h"
#include "layers/data/dataset.h"
#include "layers/data/dataset_writer.h"
#include "synthetic_sequence.h"

namespace layers::data {
namespace {

TEST(DataMemory, RandomWindowsOverALargeDatasetStayBounded) {
  testing::TempDir dir;
  testing::SyntheticSize size;
  size.frames = 60;
  size.body_rows = 40;
  size.body_cols = 100;  // 4,000 body vertices
  size.garment_rows = 100;
  size.garment_cols = 120;  // 12,000 vertices per garment
  const int n_sequences = 6;
  std::size_t position_bytes = 0;
  Timer write_timer;
  {
    DatasetWriterOptions options;
    options.sequences_per_shard = 2;
    DatasetWriter writer(dir.path(), options);
    std::vector<std::string> ids;
    for (int i = 0; i < n_sequences; ++i) {
      const SequenceData seq = testing::make_sequence("m" + std::to_string(i), 50 + i, size);
      position_bytes += seq.body.positions.size() * sizeof(float);
      for (const auto& g : seq.garments) position_bytes += g.positions.size() * sizeof(float);
      writer.add(seq);
      ids.push_back(seq.id);
    }
    writer.set_split("train", ids);
    writer.finish();
  }
  const double write_s = write_timer.seconds();

  const std::size_t before = resident_bytes();
  ReaderOptions options;
  options.cache_bytes = 8u << 20;
  Timer read_timer;
  const Dataset ds = Dataset::open(dir.path(), options);
  std::mt19937 rng(1234);
  std::size_t window_bytes = 0, peak_growth = 0;
  for (int i = 0; i < 100; ++i) {
    const std::string id = "m" + std::to_string(rng() % n_sequences);
    const std::int64_t start = 1 + static_cast<std::int64_t>(rng() % 55);
    const Window w = ds.read_window(id, start, 1, 3);
    const auto statics = ds.statics(id);
    ASSERT_EQ(w.n_frames, 5);
    ASSERT_EQ(w.garments[1].size(), 5u * 12000u * 3u);
    ASSERT_EQ(statics->garments[0].rest.size(), 12000u * 3u);
    window_bytes = w.body.positions.size() * 4 + (w.garments[0].size() + w.garments[1].size()) * 4;
    const std::size_t now = resident_bytes();
    if (now > before) peak_growth = std::max(peak_growth, now - before);
  }
  const double read_s = read_timer.seconds();
  const std::size_t after = resident_bytes();
  const std::size_t growth = after > before ? after - before : 0;
  const CacheStats cache = ds.cache_stats();
  std::printf(
      "[memory] dataset: %d sequences, %.1f MiB of positions (written in %.2f s); reader cache %.1f MiB\n"
      "[memory] 100 random windows of 5 frames (%.2f MiB each) + statics in %.2f s\n"
      "[memory] resident before %.1f MiB, after %.1f MiB, growth %.1f MiB (peak growth %.1f MiB; bound 64 MiB)\n"
      "[memory] statics cache: %.2f MiB in %zu entries, %zu hits, %zu misses, %zu open shard files\n",
      n_sequences, position_bytes / 1048576.0, write_s, options.cache_bytes / 1048576.0, window_bytes / 1048576.0,
      read_s, before / 1048576.0, after / 1048576.0, growth / 1048576.0, peak_growth / 1048576.0,
      cache.bytes / 1048576.0, cache.entries, cache.hits, cache.misses, cache.open_files);
  EXPECT_GT(position_bytes, 90u << 20);
  EXPECT_LE(cache.bytes, options.cache_bytes);
  EXPECT_LE(cache.open_files, options.max_open_files);
  EXPECT_LT(peak_growth, 64u << 20);
  EXPECT_LT(growth, 64u << 20);
}

}  // namespace
}  // namespace layers::data
