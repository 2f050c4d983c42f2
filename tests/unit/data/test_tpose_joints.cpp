// The optional body/tpose_joints array of LAYERS-H5: written and read back
// bit-identically when present (whole sequence and streamed statics),
// absent from files that lack it (older files stay readable and valid),
// and rejected with the object and the expected shape when misshaped or
// not finite.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "error_of.h"
#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/dataset_writer.h"
#include "layers/data/sequence.h"
#include "layers/data/stats.h"
#include "layers/data/validate.h"
#include "synthetic_sequence.h"

namespace layers::data {
namespace {

using testing::make_sequence;
using testing::TempDir;

// A T-pose per joint: a rotation about y by a joint-dependent angle and a
// position, so that every value differs.
std::vector<float> tpose_joints(int joints) {
  std::vector<float> out;
  for (int j = 0; j < joints; ++j) {
    const float a = 0.3f * float(j + 1), c = std::cos(a), s = std::sin(a);
    const float m[12] = {c, 0, s, 0.1f * j, 0, 1, 0, 0.9f + 0.05f * j, -s, 0, c, -0.02f * j};
    out.insert(out.end(), m, m + 12);
  }
  return out;
}

// Sequence "with" has T-pose joints, "without" has none.
void write_pair(const std::string& folder) {
  DatasetWriterOptions options;
  options.sequences_per_shard = 1;
  DatasetWriter writer(folder, options);
  SequenceData with = make_sequence("with", 1);
  with.body.tpose_joints = tpose_joints(static_cast<int>(with.body.n_joints()));
  writer.add(with);
  writer.add(make_sequence("without", 2));
  writer.set_split("train", {"with", "without"});
  writer.finish();
  write_dataset_stats(folder, compute_stats(Dataset::open(folder)));  // as the generator does
}

std::string all_text(const std::vector<Problem>& problems) {
  std::string out;
  for (const auto& p : problems) out += p.to_string() + "\n";
  return out;
}

TEST(TposeJoints, RoundTripWhenPresentEmptyWhenAbsent) {
  TempDir dir;
  write_pair(dir.path());
  const Dataset ds = Dataset::open(dir.path());
  const std::vector<float> expected = tpose_joints(5);

  EXPECT_TRUE(ds.info("with").has_tpose_joints);
  EXPECT_FALSE(ds.info("without").has_tpose_joints);
  EXPECT_EQ(ds.read_sequence("with").body.tpose_joints, expected);
  EXPECT_EQ(ds.statics("with")->body.tpose_joints, expected);
  EXPECT_TRUE(ds.read_sequence("without").body.tpose_joints.empty());
  EXPECT_TRUE(ds.statics("without")->body.tpose_joints.empty());
  // The rest of the sequence is unaffected by the optional array.
  testing::expect_same(make_sequence("without", 2), ds.read_sequence("without"));

  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(problems.empty()) << all_text(problems);
}

TEST(TposeJoints, WriterRejectsAWrongSize) {
  SequenceData seq = make_sequence("x", 1);
  seq.body.tpose_joints = tpose_joints(4);  // J = 5 joints
  const std::string message = test::error_of<InputError>([&] { check_sequence(seq, "out.h5"); });
  EXPECT_NE(message.find("/seq/x/body/tpose_joints"), std::string::npos) << message;
  EXPECT_NE(message.find("[J,3,4]"), std::string::npos) << message;
  EXPECT_NE(message.find("J=5"), std::string::npos) << message;
}

TEST(TposeJoints, ValidatorAndReaderRejectBadShapeAndValues) {
  TempDir dir;
  write_pair(dir.path());
  const std::string shard = dir.file("shard-00000.h5");

  testing::poke(shard, "/seq/with/body/tpose_joints", {2, 1, 3}, std::numeric_limits<float>::infinity());
  auto problems = validate_dataset(dir.path());
  ASSERT_EQ(problems.size(), 1u) << all_text(problems);
  EXPECT_NE(problems[0].to_string().find("/seq/with/body/tpose_joints: expected finite values"), std::string::npos)
      << all_text(problems);

  const std::vector<float> values(4 * 12, 0.0f);
  testing::replace_dataset(shard, "/seq/with/body/tpose_joints", H5::PredType::NATIVE_FLOAT, {4, 3, 4}, values.data());
  problems = validate_dataset(dir.path());
  ASSERT_FALSE(problems.empty());
  EXPECT_NE(all_text(problems).find("/seq/with/body/tpose_joints: expected float32 [J,3,4] with J=5"),
            std::string::npos)
      << all_text(problems);
  const std::string error = test::error_of<InputError>([&] { Dataset::open(dir.path()); });
  EXPECT_NE(error.find("/seq/with/body/tpose_joints"), std::string::npos) << error;
}

}  // namespace
}  // namespace layers::data
