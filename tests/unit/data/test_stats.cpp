// Normalisation statistics: hand-computed values on a tiny case, train
// split only, the std floor, errors and the stats.h5 round trip.
#include <gtest/gtest.h>

#include <cmath>

#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/dataset_writer.h"
#include "layers/data/stats.h"
#include "synthetic_sequence.h"

namespace layers::data {
namespace {

using testing::make_sequence;
using testing::TempDir;

// 3 frames, 4 body and 4 garment vertices, root x = 0, 1, 3. Relative to
// the root, garment vertex v at frame t is (v, t^2, 0) and body vertex v
// is (0, 0, v t).
SequenceData tiny_sequence() {
  testing::SyntheticSize size;
  size.frames = 3;
  size.body_rows = size.body_cols = 2;
  size.garment_rows = size.garment_cols = 2;
  size.joints = 2;
  size.garments = 1;
  SequenceData seq = make_sequence("tiny", 5, size);
  const float root_x[3] = {0, 1, 3};
  for (int t = 0; t < 3; ++t) {
    seq.body.root[3 * t] = root_x[t];
    seq.body.root[3 * t + 1] = 0.0f;
    seq.body.root[3 * t + 2] = 0.0f;
    for (int v = 0; v < 4; ++v) {
      float* g = &seq.garments[0].positions[(t * 4 + v) * 3];
      g[0] = root_x[t] + float(v);
      g[1] = float(t * t);
      g[2] = 0.0f;
      float* b = &seq.body.positions[(t * 4 + v) * 3];
      b[0] = root_x[t];
      b[1] = 0.0f;
      b[2] = float(v * t);
    }
  }
  return seq;
}

void write_stats_dataset(const std::string& folder, bool empty_train = false) {
  DatasetWriter writer(folder);
  writer.add(tiny_sequence());
  writer.add(make_sequence("big", 9));  // very different values, in val only
  writer.set_split("train", empty_train ? std::vector<std::string>{} : std::vector<std::string>{"tiny"});
  writer.set_split("val", {"big"});
  writer.finish();
}

TEST(DataStats, HandComputedTinyCaseFromTrainOnly) {
  TempDir dir;
  write_stats_dataset(dir.path());
  const NormStats s = compute_stats(Dataset::open(dir.path()));
  const double floor = 1e-6, eps = 1e-9;
  EXPECT_EQ(s.split, "train");
  EXPECT_EQ(s.n_sequences, 1);
  EXPECT_EQ(s.n_frames, 3);
  // Garment positions: x in {0,1,2,3} -> mean 1.5, var 1.25; y = t^2 in
  // {0,1,4} -> mean 5/3, var 17/3 - 25/9 = 26/9; z = 0 -> floored.
  EXPECT_EQ(s.garment_position.count, 12);
  EXPECT_NEAR(s.garment_position.mean[0], 1.5, eps);
  EXPECT_NEAR(s.garment_position.std[0], std::sqrt(1.25), eps);
  EXPECT_NEAR(s.garment_position.mean[1], 5.0 / 3.0, eps);
  EXPECT_NEAR(s.garment_position.std[1], std::sqrt(26.0) / 3.0, eps);
  EXPECT_NEAR(s.garment_position.mean[2], 0.0, eps);
  EXPECT_EQ(s.garment_position.std[2], floor);
  // Velocities: y = 1 (t=1), 3 (t=2) -> mean 2, std 1; x, z zero.
  EXPECT_EQ(s.garment_velocity.count, 8);
  EXPECT_NEAR(s.garment_velocity.mean[1], 2.0, eps);
  EXPECT_NEAR(s.garment_velocity.std[1], 1.0, eps);
  EXPECT_NEAR(s.garment_velocity.mean[0], 0.0, eps);
  EXPECT_EQ(s.garment_velocity.std[0], floor);
  // Acceleration: y = 3 - 1 = 2 at t=2 only.
  EXPECT_EQ(s.garment_acceleration.count, 4);
  EXPECT_NEAR(s.garment_acceleration.mean[1], 2.0, eps);
  EXPECT_EQ(s.garment_acceleration.std[1], floor);
  // Body: z = v t -> values {0,0,0,0, 0,1,2,3, 0,2,4,6}: mean 1.5,
  // var 70/12 - 2.25 = 43/12; velocity z = v twice: mean 1.5, var 1.25;
  // acceleration 0.
  EXPECT_NEAR(s.body_position.mean[2], 1.5, eps);
  EXPECT_NEAR(s.body_position.std[2], std::sqrt(43.0 / 12.0), eps);
  EXPECT_NEAR(s.body_position.mean[0], 0.0, eps);
  EXPECT_NEAR(s.body_velocity.mean[2], 1.5, eps);
  EXPECT_NEAR(s.body_velocity.std[2], std::sqrt(1.25), eps);
  EXPECT_NEAR(s.body_acceleration.mean[2], 0.0, eps);
  EXPECT_EQ(s.body_acceleration.std[2], floor);
}

TEST(DataStats, EmptyTrainSplitIsAnError) {
  TempDir dir;
  write_stats_dataset(dir.path(), true);
  try {
    compute_stats(Dataset::open(dir.path()));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("splits.yaml: train: expected at least one sequence, got an empty list"), std::string::npos)
        << message;
  }
}

TEST(DataStats, WriteReadRoundTripAndBadFile) {
  TempDir dir;
  write_stats_dataset(dir.path());
  const NormStats s = compute_stats(Dataset::open(dir.path()));
  const std::string path = dir.file("stats.h5");
  write_stats(path, s);
  const NormStats back = read_stats(path);
  EXPECT_EQ(back.split, "train");
  EXPECT_EQ(back.n_frames, 3);
  EXPECT_EQ(back.garment_position.mean, s.garment_position.mean);
  EXPECT_EQ(back.garment_position.std, s.garment_position.std);
  EXPECT_EQ(back.body_acceleration.std, s.body_acceleration.std);
  EXPECT_EQ(back.garment_velocity.count, 8);

  testing::remove_object(path, "/body/velocity/std");
  try {
    read_stats(path);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/body/velocity/std"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace layers::data
