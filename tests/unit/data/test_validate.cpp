// The validator on good and bad datasets, one bad input per test, each
// checking that the problem names the file, object and what was expected;
// and the reader's errors for the same inputs.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

#include "error_of.h"
#include "layers/core/error.h"
#include "layers/data/content_hash.h"
#include "layers/data/dataset.h"
#include "layers/data/dataset_writer.h"
#include "layers/data/manifest.h"
#include "layers/data/stats.h"
#include "layers/data/validate.h"
#include "synthetic_sequence.h"

namespace layers::data {
namespace {

using testing::make_sequence;
using testing::TempDir;

void write_good(const std::string& folder) {
  DatasetWriterOptions options;
  options.sequences_per_shard = 1;
  DatasetWriter writer(folder, options);
  writer.add(make_sequence("a", 1));
  writer.add(make_sequence("b", 2));
  writer.set_split("train", {"a"});
  writer.set_split("val", {});
  writer.set_split("test", {"b"});
  writer.finish();
  write_dataset_stats(folder, compute_stats(Dataset::open(folder)));  // as the generator does
}

std::string all_text(const std::vector<Problem>& problems) {
  std::string out;
  for (const auto& p : problems) out += p.to_string() + "\n";
  return out;
}

// The one problem whose text contains `needle` (fails if none).
::testing::AssertionResult has_problem(const std::vector<Problem>& problems, const std::string& needle) {
  for (const auto& p : problems) {
    if (p.to_string().find(needle) != std::string::npos) return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "no problem mentions '" << needle << "' in:\n" << all_text(problems);
}

std::string open_error(const std::string& path) {
  try {
    Dataset::open(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

class DataValidate : public ::testing::Test {
 protected:
  void SetUp() override { write_good(dir.path()); }
  std::string shard(int i) const { return dir.file("shard-0000" + std::to_string(i) + ".h5"); }
  TempDir dir;
};

TEST_F(DataValidate, GoodDatasetHasNoProblems) {
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(problems.empty()) << all_text(problems);
  EXPECT_TRUE(validate_dataset(shard(0)).empty());
}

TEST_F(DataValidate, TruncatedFile) {
  std::filesystem::resize_file(shard(1), std::filesystem::file_size(shard(1)) / 2);
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(has_problem(problems, "shard-00001.h5: cannot open the HDF5 file")) << all_text(problems);
  EXPECT_TRUE(has_problem(problems, "truncated"));
  // The other shard is still checked, and the split naming b is flagged.
  EXPECT_TRUE(has_problem(problems, "got 'b' (in no shard)"));
  const std::string error = open_error(dir.path());
  EXPECT_NE(error.find("shard-00001.h5"), std::string::npos) << error;
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;
}

TEST_F(DataValidate, NotAnHdf5File) {
  testing::write_text(shard(0), "this is not HDF5\n");
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(has_problem(problems, "shard-00000.h5: expected an HDF5 file, got no HDF5 signature"));
}

TEST_F(DataValidate, MissingDataset) {
  testing::remove_object(shard(0), "/seq/a/body/root_rot");
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(has_problem(problems, "/seq/a/body/root_rot: missing dataset (expected float32 [T,4])"));
  const std::string error = open_error(dir.path());
  EXPECT_NE(error.find("/seq/a/body/root_rot: missing dataset"), std::string::npos) << error;
}

TEST_F(DataValidate, WrongShape) {
  const std::vector<float> values(12 * 127 * 3, 0.5f);  // one vertex short of the rest shape
  testing::replace_dataset(shard(1), "/seq/b/garments/0/positions", H5::PredType::NATIVE_FLOAT, {12, 127, 3},
                           values.data());
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(has_problem(problems,
                          "/seq/b/garments/0/positions: expected float32 [T,V,3] with V=128 (as in "
                          "/seq/b/garments/0/rest), got [12,127,3]"));
  const std::vector<float> rows(11 * 4, 0.0f);
  testing::replace_dataset(shard(1), "/seq/b/wind/rotation", H5::PredType::NATIVE_FLOAT, {11, 4}, rows.data());
  EXPECT_TRUE(has_problem(validate_dataset(dir.path()), "/seq/b/wind/rotation: expected float32 [T,4] with T=12"));
}

TEST_F(DataValidate, WrongDtype) {
  const std::vector<double> values(12 * 200 * 3, 0.25);
  testing::replace_dataset(shard(0), "/seq/a/body/positions", H5::PredType::NATIVE_DOUBLE, {12, 200, 3}, values.data());
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(has_problem(problems, "/seq/a/body/positions: expected dtype float32, got float64"));
  const std::string error = open_error(dir.path());
  EXPECT_NE(error.find("expected dtype float32, got float64"), std::string::npos) << error;
}

TEST_F(DataValidate, NaNInPositions) {
  testing::poke(shard(0), "/seq/a/garments/1/positions", {7, 3, 1}, std::numeric_limits<float>::quiet_NaN());
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(has_problem(
      problems, "/seq/a/garments/1/positions: expected finite values, got 1 non-finite (first NaN at [7,3,1])"));
}

TEST_F(DataValidate, FacesOutOfRange) {
  testing::poke(shard(1), "/seq/b/body/faces", {4, 2}, std::int32_t{200});
  testing::poke(shard(1), "/seq/b/garments/0/uv_faces", {0, 0}, std::int32_t{-1});
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(
      has_problem(problems, "/seq/b/body/faces: expected indices in [0,199], got 1 out of range, first 200 at row 4"));
  EXPECT_TRUE(has_problem(problems, "/seq/b/garments/0/uv_faces: expected indices in [0,127]"));
}

TEST_F(DataValidate, WindOutOfRangeAndNonUnitQuaternion) {
  testing::poke(shard(0), "/seq/a/wind/strength", {3}, 450.0f);
  testing::poke(shard(0), "/seq/a/wind/rotation", {2, 0}, 3.0f);
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(
      has_problem(problems, "/seq/a/wind/strength: expected strengths in [0,400], got 1 outside (first 450 at [3])"));
  EXPECT_TRUE(has_problem(problems, "/seq/a/wind/rotation: expected unit quaternions"));
  EXPECT_TRUE(has_problem(problems, "at frame [2,0]"));
}

TEST_F(DataValidate, SplitNamingAnUnknownSequence) {
  testing::write_text(dir.file("splits.yaml"), "train: [a]\nval: []\ntest:\n  - b\n  - zzz\n");
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(has_problem(problems,
                          "splits.yaml:5: test: expected ids of sequences in the dataset's shards, got 'zzz' (in no "
                          "shard)"))
      << all_text(problems);
  const std::string error = open_error(dir.path());
  EXPECT_NE(error.find("splits.yaml:5: test"), std::string::npos) << error;
  EXPECT_NE(error.find("got 'zzz' (in no shard)"), std::string::npos) << error;
}

TEST_F(DataValidate, MalformedSplitsYaml) {
  testing::write_text(dir.file("splits.yaml"), "train: [a]\nval: [b\ntest: []\n");
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(has_problem(problems, "splits.yaml:3: malformed YAML")) << all_text(problems);
  const std::string error = open_error(dir.path());
  EXPECT_NE(error.find("splits.yaml:3: malformed YAML"), std::string::npos) << error;

  testing::write_text(dir.file("splits.yaml"), "train: a\n");
  EXPECT_TRUE(has_problem(validate_dataset(dir.path()), "splits.yaml:1: train: expected a list of sequence ids"));
}

// Issue 62 message 7: a split the file lacks is named with the file's path
// (which dataset), not a bare "splits.yaml".
TEST_F(DataValidate, AMissingSplitNamesTheDatasetsFile) {
  const Dataset ds = Dataset::open(dir.path());
  const std::string said = test::error_of<InputError>([&] { ds.splits().get("nope"); });
  EXPECT_EQ(said.rfind(dir.file("splits.yaml") + ": nope: expected a split named 'nope', got only train", 0), 0u)
      << said;
}

TEST_F(DataValidate, MissingDatasetYaml) {
  std::filesystem::remove(dir.file("dataset.yaml"));
  EXPECT_TRUE(has_problem(validate_dataset(dir.path()), "dataset.yaml: missing"));
  EXPECT_NE(open_error(dir.path()).find("dataset.yaml"), std::string::npos);
}

TEST_F(DataValidate, DuplicateIdsAcrossShards) {
  std::filesystem::copy_file(shard(0), dir.file("shard-00002.h5"));
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(has_problem(problems, "shard-00002.h5: /seq/a: duplicate sequence id: also in"));
  // The reader stops at the first problem: a shard file dataset.yaml does not list.
  EXPECT_NE(open_error(dir.path())
                .find("shards: expected only the listed shard files, got 1 more in the folder: "
                      "shard-00002.h5"),
            std::string::npos)
      << open_error(dir.path());
}

TEST_F(DataValidate, WrongRootAttributes) {
  {
    H5::H5File f(shard(0), H5F_ACC_RDWR);
    H5::Group root = f.openGroup("/");
    root.removeAttr("format_version");
    const std::int64_t two = 2;
    root.createAttribute("format_version", H5::PredType::STD_I64LE, H5::DataSpace(H5S_SCALAR))
        .write(H5::PredType::NATIVE_INT64, &two);
    root.removeAttr("units");
  }
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(has_problem(problems, "/ attribute format_version: expected 1, got 2"));
  EXPECT_TRUE(has_problem(problems, "/ attribute units: expected a string, got nothing (missing)"));
}

TEST_F(DataValidate, ReportsEveryProblemNotJustTheFirst) {
  testing::poke(shard(0), "/seq/a/body/positions", {0, 0, 0}, std::numeric_limits<float>::infinity());
  testing::poke(shard(0), "/seq/a/garments/0/faces", {1, 1}, std::int32_t{999});
  testing::remove_object(shard(1), "/seq/b/body/joint_names");
  testing::write_text(dir.file("splits.yaml"), "train: [a, ghost]\ntest: [b]\n");
  const auto problems = validate_dataset(dir.path());
  EXPECT_TRUE(has_problem(problems, "/seq/a/body/positions: expected finite values"));
  EXPECT_TRUE(has_problem(problems, "/seq/a/garments/0/faces: expected indices in [0,127]"));
  EXPECT_TRUE(has_problem(problems, "/seq/b/body/joint_names: missing dataset"));
  EXPECT_TRUE(has_problem(problems, "got 'ghost' (in no shard)"));
  EXPECT_EQ(problems.size(), 4u) << all_text(problems);
}

// A finished dataset of one synthetic sequence "s" in the test split.
SequenceData write_one(const std::string& folder) {
  DatasetWriter writer(folder, DatasetWriterOptions{});
  const SequenceData seq = make_sequence("s", 1);
  writer.add(seq);
  writer.set_split("train", {});
  writer.set_split("test", {"s"});
  writer.finish();
  return seq;
}

// Ground truth out of physical bounds is an input error of the data,
// naming file, sequence, array, frame and vertex -- in the reader (so
// train and eval never blame a model for it) and in `layers validate`.
TEST(DataBounds, AbsurdOrNonFiniteFramesAreInputErrors) {
  // A good dataset damaged afterwards (through HDF5, so the chunk checksums
  // still match): the value checks must catch what the checksums cannot.
  // The validator's own scan reports non-finite values first, in its words.
  auto expect_refused = [](const std::string& object, const std::vector<hsize_t>& index, float value,
                           const std::string& needle, const std::string& validator_needle = "") {
    TempDir dir;
    const std::string folder = dir.file("ds");
    const SequenceData seq = write_one(folder);
    testing::poke(folder + "/shard-00000.h5", object, index, value);
    const Dataset ds = Dataset::open(folder);
    const std::string message = layers::test::error_of([&] { ds.read_frames("s", 0, seq.n_frames); });
    EXPECT_NE(message.find(needle), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_TRUE(has_problem(validate_dataset(folder), validator_needle.empty() ? needle : validator_needle));
  };
  expect_refused("/seq/s/garments/0/positions", {3, 17, 1}, std::numeric_limits<float>::quiet_NaN(),
                 "/seq/s/garments/0/positions: expected finite values, got nan at frame 3, vertex 17",
                 "/seq/s/garments/0/positions: expected finite values, got 1 non-finite (first NaN at [3,17,1])");
  expect_refused("/seq/s/body/positions", {0, 5, 0}, 2.5e38f,
                 "/seq/s/body/positions: expected positions within 10 m of the body root, got 2.5e+38 m away "
                 "at frame 0, vertex 5");
}

// A bad index in the static arrays is blamed on the shard it is in when the
// sequence is read, not on a file written later from it.
TEST(DataBounds, BadJointParentIsBlamedOnTheShard) {
  TempDir dir;
  const std::string folder = dir.file("ds");
  write_one(folder);
  testing::poke(folder + "/shard-00000.h5", "/seq/s/body/joint_parents", {2}, std::int32_t{99});
  const Dataset ds = Dataset::open(folder);
  const std::string message = layers::test::error_of([&] { ds.statics("s"); });
  EXPECT_EQ(message.rfind(folder + "/shard-00000.h5: /seq/s/body/joint_parents: ", 0), 0u) << message;
}

// A dataset with a train split needs its statistics: validate says so
// instead of passing what eval would refuse.
TEST(DataBounds, MissingStatsIsAProblem) {
  TempDir dir;
  const std::string folder = dir.file("ds");
  DatasetWriter writer(folder, DatasetWriterOptions{});
  writer.add(make_sequence("s", 1));
  writer.set_split("train", {"s"});
  writer.finish();
  EXPECT_TRUE(has_problem(validate_dataset(folder), "stats.h5: missing (train, eval and bench need"));
}

// dataset.yaml records each sequence's content hash; a sequence changed
// afterwards -- even to values within every bound -- fails validation.
TEST(DataBounds, ContentHashesCatchAChangedSequence) {
  TempDir dir;
  const std::string folder = dir.file("ds");
  const SequenceData seq = write_one(folder);
  const DatasetManifest manifest = read_manifest(folder + "/dataset.yaml");
  ASSERT_EQ(manifest.content_hashes.size(), 1u);
  EXPECT_EQ(manifest.content_hashes.at("s"), sequence_content_hash(seq));
  EXPECT_TRUE(validate_dataset(folder).empty());
  testing::poke(folder + "/shard-00000.h5", "/seq/s/garments/1/positions", {2, 3, 0}, 0.25f);
  EXPECT_TRUE(has_problem(validate_dataset(folder), "content_hashes.s: expected " + sequence_content_hash(seq)));
}

}  // namespace
}  // namespace layers::data
