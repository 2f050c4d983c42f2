// tests/adversarial/test_adversarial_data.cpp -- issue 44's S1-S7 as an
// adversarial user made them, against the `layers` binary: a dataset (or
// stats.h5, splits.yaml, dataset.yaml, a checkpoint) damaged or edited in
// a way HDF5's own checksums do not see. Each must end `train`, `eval` and
// `validate` with exit 1 and one line, before anything is written; no case
// may give exit 0 with values other than the clean ones.
#include <gtest/gtest.h>

#include <H5Cpp.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>

#include "adversarial_fixture.h"
#include "file_bytes.h"
#include "probe.h"
#include "run_command.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;
using test::run_command;

namespace {

std::size_t lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

class Adversarial : public ::testing::Test {
 protected:
  // One clean dataset and a run trained on it, shared by the cases.
  static void SetUpTestSuite() {
    root_ = new test::TempDir("layers-adversarial");
    // Only the test model's plugin (the test plugin folder also holds
    // broken ones, each refused with a warning line).
    plugins_ = root_->file("plugins");
    fs::create_directories(plugins_);
    const std::string plugin = "liblayers_plugin_test_constant_velocity.so";
    fs::create_symlink(test::plugin_dir() + "/" + plugin, plugins_ + "/" + plugin);
    clean_ = test::write_two_shards(root_->file("clean"));
    experiment_ = root_->write("exp.yaml",
                               "model: {name: test_constant_velocity, params: {damping: 0.6}}\n"
                               "data: {dataset: " +
                                   clean_ +
                                   "}\n"
                                   "train: {epochs: 1, batch_size: 2, windows_per_epoch: 2, "
                                   "val_horizon: 2, val_sequences: 1}\n"
                                   "eval: {horizon: 4, save_predictions: false}\n"
                                   "run: {output: " +
                                   root_->file("run") + ", threads: 1, seed: 0}\n");
    const auto trained = layers("train " + experiment_ + " --quiet");
    ASSERT_EQ(trained.exit_code, 0) << trained.output;
    const auto clean_eval = layers("eval " + experiment_ + " --quiet --out " + root_->file("clean-eval"));
    ASSERT_EQ(clean_eval.exit_code, 0) << clean_eval.output;
    clean_metrics_ = metrics_of(root_->file("clean-eval"));
  }
  static void TearDownTestSuite() {
    delete root_;
    root_ = nullptr;
  }

  static test::CommandResult layers(const std::string& args) {
    return run_command("LAYERS_PLUGIN_PATH=" + plugins_ + " " + test::layers_bin() + " " + args);
  }
  // metrics.json without what differs between two runs of the same data.
  static std::string metrics_of(const std::string& out) {
    std::string text = test::read_bytes(out + "/metrics.json");
    for (const char* key : {"dataset", "ms_per_frame", "seconds", "experiment"})
      text = std::regex_replace(text, std::regex("\"" + std::string(key) + "\": [^,\\n]*"), "");
    return text;
  }

  // A fresh copy of the clean dataset.
  std::string copy(const std::string& name) const {
    const std::string dst = dir_.file(name);
    fs::copy(clean_, dst, fs::copy_options::recursive);
    return dst;
  }

  // `verb` (train or eval) on `dataset`: exit 1, one line naming `expect`,
  // nothing written, the dataset unchanged.
  void refused(const std::string& verb, const std::string& dataset, const std::string& expect) const {
    const auto before = test::snapshot(dataset);
    const std::string out = dir_.file(verb + "-out-" + fs::path(dataset).filename().string());
    const std::string where = verb == "train" ? " --set run.output=" + out : " --out " + out;
    const auto r = layers(verb + " " + experiment_ + " --quiet --set data.dataset=" + dataset + where);
    EXPECT_EQ(r.exit_code, 1) << verb << ": " << r.output;
    EXPECT_EQ(lines(r.output), 1u) << verb << ": " << r.output;
    EXPECT_EQ(r.output.rfind("layers: error: ", 0), 0u) << verb << ": " << r.output;
    EXPECT_NE(r.output.find(expect), std::string::npos) << verb << ": " << r.output;
    EXPECT_FALSE(fs::exists(out)) << verb << " wrote " << out;
    EXPECT_EQ(test::snapshot(dataset), before) << verb << " changed the dataset";
  }
  void invalid(const std::string& dataset, const std::string& expect) const {
    const auto r = layers("validate " + dataset);
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find(expect), std::string::npos) << r.output;
  }

  static test::TempDir* root_;
  static std::string clean_, experiment_, clean_metrics_, plugins_;
  test::TempDir dir_{"layers-adversarial-case"};
};

test::TempDir* Adversarial::root_ = nullptr;
std::string Adversarial::clean_, Adversarial::experiment_, Adversarial::clean_metrics_, Adversarial::plugins_;

// Offsets of the v1 B-tree nodes ("TREE") of a file: the chunk indices
// HDF5 does not checksum.
std::vector<std::size_t> btree_nodes(const std::string& bytes) {
  std::vector<std::size_t> out;
  for (std::size_t at = bytes.find("TREE"); at != std::string::npos; at = bytes.find("TREE", at + 4)) out.push_back(at);
  return out;
}

}  // namespace

// S1: a flipped byte in a chunk index makes a chunk "missing", and HDF5
// returns zeros without an error. Every such flip now either changes
// nothing or is refused; at least one is refused by the content hash.
TEST_F(Adversarial, S1_ChunkIndexFlipsAreRefusedOrHarmless) {
  const std::string shard_name = "shard-00001.h5";  // holds the test split
  const std::string original = test::read_bytes(clean_ + "/" + shard_name);
  const auto nodes = btree_nodes(original);
  ASSERT_GE(nodes.size(), 4u);
  int refused_by_hash = 0, refused_other = 0, unchanged = 0, tried = 0;
  for (std::size_t k = 0; k < nodes.size() && tried < 10; k += std::max<std::size_t>(1, nodes.size() / 10), ++tried) {
    // The low byte of the first chunk offset of the node's first key
    // (header 24 bytes, then chunk size and filter mask).
    const std::string data = copy("s1-" + std::to_string(k));
    std::string bytes = original;
    bytes[nodes[k] + 24 + 8] = static_cast<char>(bytes[nodes[k] + 24 + 8] ^ 0x01);
    std::ofstream(data + "/" + shard_name, std::ios::binary | std::ios::trunc) << bytes;
    const std::string out = dir_.file("s1-eval-" + std::to_string(k));
    const auto r = layers("eval " + experiment_ + " --quiet --set data.dataset=" + data + " --out " + out);
    if (r.exit_code == 0) {
      ++unchanged;
      EXPECT_EQ(metrics_of(out), clean_metrics_) << "flip in node " << k << " changed the results silently";
    } else {
      ++refused_other;
      EXPECT_EQ(r.exit_code, 1) << r.output;
      EXPECT_EQ(lines(r.output), 1u) << r.output;
      EXPECT_FALSE(fs::exists(out));
      if (r.output.find("changed since it was written") != std::string::npos) {
        ++refused_by_hash, --refused_other;
        invalid(data, "changed since it was written");
      }
    }
  }
  std::printf("S1: %d flips: %d refused by a content hash, %d by another check, %d left the results as they were\n",
              tried, refused_by_hash, refused_other, unchanged);
  EXPECT_GE(refused_by_hash, 1) << "no flip reached the values; the case proves nothing";
}

// S2: stats.h5 edited (a mean set to zero, its HDF5 checksum valid).
TEST_F(Adversarial, S2_EditedStatisticsAreRefused) {
  const std::string data = copy("s2");
  {
    H5::H5File f(data + "/stats.h5", H5F_ACC_RDWR);
    const double zeros[3] = {0, 0, 0};
    f.openDataSet("/garment/position/mean").write(zeros, H5::PredType::NATIVE_DOUBLE);
  }
  refused("train", data, "stats.h5: expected content hash ");
  refused("eval", data, "stats.h5: expected content hash ");
  invalid(data, "(the statistics changed since they were written; remove the file and run `layers stats`");
}

// S3: the contents of a train and a test sequence swapped between shards
// (ids kept), so that eval would score a training sequence as test.
TEST_F(Adversarial, S3_SequencesSwappedBetweenShardsAreRefused) {
  const std::string data = copy("s3");
  {
    H5::H5File a(data + "/shard-00000.h5", H5F_ACC_RDWR), b(data + "/shard-00001.h5", H5F_ACC_RDWR);
    ASSERT_GE(H5Ocopy(a.getId(), "/seq/seq0", b.getId(), "/seq/moved", H5P_DEFAULT, H5P_DEFAULT), 0);
    ASSERT_GE(H5Ocopy(b.getId(), "/seq/seq4", a.getId(), "/seq/moved", H5P_DEFAULT, H5P_DEFAULT), 0);
    a.unlink("/seq/seq0");
    b.unlink("/seq/seq4");
    a.move("/seq/moved", "/seq/seq0");
    b.move("/seq/moved", "/seq/seq4");
  }
  refused("train", data, "content_hashes.seq");
  refused("eval", data, "content_hashes.seq4: expected ");
  invalid(data, "(the sequence changed since it was written)");
}

// S4: a test sequence added to the train split.
TEST_F(Adversarial, S4_ATestSequenceInTrainIsRefused) {
  const std::string data = copy("s4");
  data::testing::write_text(data + "/splits.yaml",
                            "train: [seq0, seq1, seq2, seq4]\nval: [seq3]\ntest: [seq4, seq5]\n");
  const std::string expect = "expected each sequence in one of train, val and test, got 'seq4' in both train and test";
  refused("train", data, expect);
  refused("eval", data, expect);
  invalid(data, expect);
}

// S5: counts.frames or counts.shards edited in dataset.yaml.
TEST_F(Adversarial, S5_EditedCountsAreRefused) {
  const std::string manifest = test::read_bytes(clean_ + "/dataset.yaml");
  const std::pair<const char*, const char*> edits[] = {{"frames: 120", "frames: 121"}, {"shards: 2", "shards: 3"}};
  for (const auto& [from, to] : edits) {
    ASSERT_NE(manifest.find(from), std::string::npos) << manifest;
    const std::string data = copy(std::string("s5-") + to[0]);
    std::string edited = manifest;
    edited.replace(edited.find(from), std::string(from).size(), to);
    data::testing::write_text(data + "/dataset.yaml", edited);
    const std::string key = std::string("counts.") + std::string(from).substr(0, std::string(from).find(':'));
    refused("train", data, key + ": expected ");
    refused("eval", data, key + ": expected ");
    invalid(data, key + ": expected ");
  }
}

// S6: a value changed with its chunk's checksum made to agree (a body
// vertex moved 25 cm), which HDF5 reads without complaint.
TEST_F(Adversarial, S6_AValueChangedBehindTheChecksumIsRefused) {
  const std::string data = copy("s6");
  data::testing::poke(data + "/shard-00001.h5", "/seq/seq5/body/positions", {2, 7, 0}, 0.25f);
  refused("eval", data, "content_hashes.seq5: expected ");
  invalid(data, "content_hashes.seq5: expected ");
}

// S7: a checkpoint without its header, with a flipped byte.
TEST_F(Adversarial, S7_ABareCheckpointIsRefused) {
  std::string bytes = test::read_bytes(root_->file("run") + "/checkpoint-best.pt");
  bytes = bytes.substr(bytes.find('\n') + 1);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x01);
  const std::string checkpoint = dir_.file("bare.pt");
  std::ofstream(checkpoint, std::ios::binary) << bytes;
  const std::string out = dir_.file("s7");
  const auto r = layers("eval " + experiment_ + " --quiet --checkpoint " + checkpoint + " --out " + out);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_EQ(lines(r.output), 1u) << r.output;
  EXPECT_NE(r.output.find("got a bare torch archive without a checksum"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// Issue 62 S8: with dataset.yaml's hashes gone and --allow-unhashed, a
// value changed behind the checksum was read unverified although its
// shard records the sequence's hash; it is verified against that.
TEST_F(Adversarial, S8_UnhashedReadingStillVerifiesTheShardsOwnHashes) {
  const std::string data = copy("s8");
  std::string manifest = test::read_bytes(data + "/dataset.yaml");
  manifest = std::regex_replace(manifest, std::regex("content_hashes:\\n(  .*\\n)*"), "");
  data::testing::write_text(data + "/dataset.yaml", manifest);
  data::testing::poke(data + "/shard-00001.h5", "/seq/seq5/body/positions", {2, 7, 0}, 0.25f);
  const std::string out = dir_.file("s8-eval");
  const auto r = layers("eval " + experiment_ + " --quiet --set data.dataset=" + data +
                        " --set data.allow_unhashed=true --out " + out);
  // The flag's warning, then the one error line.
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_EQ(lines(r.output), 2u) << r.output;
  EXPECT_NE(r.output.find("layers: error: " + data + "/shard-00001.h5: / attribute content_hashes.seq5: expected "),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
  // S3: recording the hashes again verifies against the shards' own first,
  // so the damaged value's hash is not recorded.
  const auto before = test::snapshot(data);
  const auto recorded = layers("validate --record-hashes " + data);
  EXPECT_EQ(recorded.exit_code, 1) << recorded.output;
  EXPECT_NE(recorded.output.find("content_hashes.seq5: expected "), std::string::npos) << recorded.output;
  EXPECT_EQ(test::snapshot(data), before);
}

// C3 (issue 62): a shard of the kind written before strings were stored
// fixed-length (a variable-length string attribute, in HDF5's global heap,
// which has no checksum) reads as before; with that heap's object size
// damaged (tests/fuzz/libhdf5-crashes: libhdf5 read past it and died) it is
// refused with one line before libhdf5 reads the string.
TEST_F(Adversarial, C3_ADamagedGlobalHeapIsRefusedBeforeLibhdf5ReadsIt) {
  const std::string data = copy("c3");
  const std::string shard = data + "/shard-00000.h5";
  {
    H5::H5File f(shard, H5F_ACC_RDWR);
    H5::Group root = f.openGroup("/");
    H5::Attribute fixed = root.openAttribute("format");
    std::string value;
    fixed.read(fixed.getStrType(), value);
    fixed.close();
    root.removeAttr("format");
    const H5::StrType variable(H5::PredType::C_S1, H5T_VARIABLE);
    const char* text = value.c_str();
    root.createAttribute("format", variable, H5::DataSpace(H5S_SCALAR)).write(variable, &text);
  }
  const auto old_kind = layers("info " + shard);
  ASSERT_EQ(old_kind.exit_code, 0) << "an intact variable-length string reads as before: " << old_kind.output;
  // The first object of the first collection made to claim 2^53 bytes.
  std::string bytes = test::read_bytes(shard);
  const std::size_t at = bytes.find(std::string("GCOL\x01\0\0\0", 8));
  ASSERT_NE(at, std::string::npos) << "no global heap collection in the shard";
  const std::uint64_t huge = std::uint64_t{1} << 53;
  for (int k = 0; k < 8; ++k) bytes[at + 16 + 8 + k] = static_cast<char>((huge >> (8 * k)) & 0xff);
  {
    std::ofstream out(shard, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  const std::string expect = shard + ": global heap: expected intact variable-length strings";
  for (const std::string& verb : {std::string("info ") + shard, std::string("validate ") + data}) {
    const auto r = layers(verb);
    EXPECT_EQ(r.exit_code, 1) << verb << ": " << r.output;
    EXPECT_EQ(lines(r.output), 1u) << verb << ": " << r.output;
    EXPECT_NE(r.output.find(expect), std::string::npos) << verb << ": " << r.output;
    EXPECT_NE(r.output.find("object 1 of 9007199254740992 bytes"), std::string::npos) << r.output;
  }
  refused("eval", data, expect);
}

// A dataset written before content hashes is refused, read with the flag
// (which metrics.json records), and migrated by `validate --record-hashes`.
TEST_F(Adversarial, UnhashedDatasetsNeedTheFlagAndMigrate) {
  const std::string data = copy("old");
  std::string manifest = test::read_bytes(data + "/dataset.yaml");
  manifest = std::regex_replace(manifest, std::regex("content_hashes:\\n(  .*\\n)*"), "");
  manifest = std::regex_replace(manifest, std::regex("stats_hash: .*\\n"), "");
  manifest = std::regex_replace(manifest, std::regex("shards: \\[.*\\]\\n"), "");
  data::testing::write_text(data + "/dataset.yaml", manifest);
  refused("eval", data, "content_hashes: expected a content hash per sequence, got none");
  const std::string out = dir_.file("old-eval");
  const auto allowed = layers("eval " + experiment_ + " --quiet --set data.dataset=" + data +
                              " --set data.allow_unhashed=true --out " + out);
  ASSERT_EQ(allowed.exit_code, 0) << allowed.output;
  EXPECT_NE(test::read_bytes(out + "/metrics.json").find("\"allow_unhashed\": true"), std::string::npos);
  const auto migrated = layers("validate --record-hashes " + data);
  ASSERT_EQ(migrated.exit_code, 0) << migrated.output;
  EXPECT_EQ(test::read_bytes(data + "/dataset.yaml"), test::read_bytes(clean_ + "/dataset.yaml"));
  EXPECT_EQ(layers("validate " + data).exit_code, 0);
}

// M5: a checkpoint that is a device never ends; it is refused before a
// byte is read, within the memory bound, and a real one evaluates under
// the same bound.
TEST_F(Adversarial, M5_ADeviceAsCheckpointIsRefusedBeforeReading) {
  const std::string env = "LAYERS_PLUGIN_PATH=" + plugins_;
  const test::Probe bad = test::probe(
      "eval " + experiment_ + " --quiet --checkpoint /dev/zero --out " + dir_.file("m5"), dir_.file("m5.log"), env);
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_EQ(lines(bad.output), 1u) << bad.output;
  EXPECT_NE(bad.output.find("/dev/zero: checkpoint: expected a regular file, got a device"), std::string::npos)
      << bad.output;
  EXPECT_LT(bad.peak_mib, test::kMaxPeakMiB);
  EXPECT_FALSE(fs::exists(dir_.file("m5")));
  const test::Probe good =
      test::probe("eval " + experiment_ + " --quiet --out " + dir_.file("m5-good"), dir_.file("m5-good.log"), env);
  EXPECT_EQ(good.exit_code, 0) << good.output;
  EXPECT_LT(good.peak_mib, test::kMaxPeakMiB);
}
