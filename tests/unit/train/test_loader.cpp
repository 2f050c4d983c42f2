// The window loader: which windows, in which order, in which batches.
#include <gtest/gtest.h>

#include <set>

#include "layers/core/error.h"
#include "layers/train/window_loader.h"
#include "temp_dir.h"
#include "train_fixture.h"

namespace layers::train {
namespace {

using Keys = std::vector<std::pair<std::string, std::int64_t>>;

Keys epoch_keys(WindowLoader& loader, int epoch, std::int64_t horizon, std::vector<std::size_t>* sizes = nullptr) {
  Keys keys;
  loader.start_epoch(epoch, horizon);
  while (auto batch = loader.next()) {
    if (sizes) sizes->push_back(batch->size());
    for (const Sample& s : *batch) {
      EXPECT_EQ(s.frames.frames(), 1 + 1 + horizon);
      EXPECT_EQ(s.frames.first_frame, s.start - 1);
      keys.emplace_back(s.id, s.start);
    }
  }
  return keys;
}

TEST(WindowLoader, EveryWindowOncePerEpochInBatches) {
  test::TempDir dir;
  const data::Dataset ds = data::Dataset::open(testing::write_dataset(dir.path() + "/d", 5, 12));
  LoaderOptions o;
  o.batch_size = 4;
  o.prefetch = 1;  // the producer waits on the consumer
  WindowLoader loader(ds, o);
  ASSERT_EQ(loader.sequences().size(), 3u);
  // 12 frames, history 1, horizon 2: starts 1..9 -> 9 windows per sequence.
  EXPECT_EQ(loader.windows(2), 27u);
  std::vector<std::size_t> sizes;
  const Keys keys = epoch_keys(loader, 0, 2, &sizes);
  EXPECT_EQ(keys.size(), 27u);
  const std::set<std::pair<std::string, std::int64_t>> unique(keys.begin(), keys.end());
  EXPECT_EQ(unique.size(), 27u);
  EXPECT_EQ(sizes, (std::vector<std::size_t>{4, 4, 4, 4, 4, 4, 3}));
  // A longer horizon (curriculum) leaves fewer windows.
  EXPECT_EQ(epoch_keys(loader, 1, 5).size(), 18u);
}

TEST(WindowLoader, OrderIsSeededAndChangesPerEpoch) {
  test::TempDir dir;
  const data::Dataset ds = data::Dataset::open(testing::write_dataset(dir.path() + "/d", 5, 12));
  LoaderOptions o;
  o.seed = 11;
  WindowLoader a(ds, o), b(ds, o);
  const Keys a0 = epoch_keys(a, 0, 2), b0 = epoch_keys(b, 0, 2), a1 = epoch_keys(a, 1, 2);
  EXPECT_EQ(a0, b0);
  EXPECT_NE(a0, a1);
  o.seed = 12;
  WindowLoader c(ds, o);
  EXPECT_NE(epoch_keys(c, 0, 2), a0);
}

TEST(WindowLoader, SubsetsLimitsAndInnerOnly) {
  test::TempDir dir;
  const data::Dataset ds = data::Dataset::open(testing::write_dataset(dir.path() + "/d", 5, 12));
  LoaderOptions o;
  o.subsets = {"T"};  // s0 (train) and s4 (test): train keeps s0 only
  o.windows_per_epoch = 5;
  o.selection.inner_only = true;
  WindowLoader loader(ds, o);
  ASSERT_EQ(loader.sequences(), std::vector<std::string>{"s0"});
  loader.start_epoch(0, 2);
  std::size_t n = 0;
  while (auto batch = loader.next()) {
    for (const Sample& s : *batch) {
      ++n;
      ASSERT_EQ(s.frames.garments.size(), 1u);  // the outer jacket dropped
      ASSERT_EQ(s.statics->garments.size(), 1u);
      EXPECT_EQ(s.statics->garments[0].layer, 0);
    }
  }
  EXPECT_EQ(n, 5u);
}

TEST(WindowLoader, TooShortSequencesAreAClearError) {
  test::TempDir dir;
  const data::Dataset ds = data::Dataset::open(testing::write_dataset(dir.path() + "/d", 4, 6));
  WindowLoader loader(ds, LoaderOptions{});
  try {
    loader.start_epoch(0, 6);
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("none long enough"), std::string::npos) << e.what();
  }
}

TEST(WindowLoader, UnknownSubsetNamesTheSplitsFile) {
  test::TempDir dir;
  const data::Dataset ds = data::Dataset::open(testing::write_dataset(dir.path() + "/d", 4, 8));
  LoaderOptions o;
  o.subsets = {"L+W"};
  EXPECT_THROW(WindowLoader(ds, o), InputError);
}

}  // namespace
}  // namespace layers::train
