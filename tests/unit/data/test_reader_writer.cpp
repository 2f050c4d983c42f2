// Round trips through the writers and the streaming reader: bit-identical
// sequences, windows equal to slices, errors for bad windows and ids,
// bounded statics cache, concurrent reads, atomic and resumable writing.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "error_of.h"
#include "layers/core/error.h"
#include "layers/core/text_file.h"
#include "layers/data/dataset.h"
#include "layers/data/dataset_writer.h"
#include "layers/data/manifest.h"
#include "layers/data/shard_writer.h"
#include "synthetic_sequence.h"

namespace layers::data {
namespace {

using testing::expect_same;
using testing::make_sequence;
using testing::TempDir;

// Writes a dataset of `n` synthetic sequences s0..s(n-1), one per shard
// unless told otherwise; train = all but the last, test = the last.
std::vector<SequenceData> write_dataset(const std::string& folder, int n, std::int64_t per_shard = 1) {
  std::vector<SequenceData> seqs;
  DatasetWriterOptions options;
  options.name = "tiny";
  options.seed = 7;
  options.sequences_per_shard = per_shard;
  options.generator_config_yaml = "body: {gender: 0.5}\nframes: 12\n";
  DatasetWriter writer(folder, options);
  std::vector<std::string> train;
  for (int i = 0; i < n; ++i) {
    seqs.push_back(make_sequence("s" + std::to_string(i), 100 + i));
    writer.add(seqs.back());
    if (i + 1 < n) train.push_back(seqs.back().id);
  }
  writer.set_split("train", train);
  writer.set_split("test", {seqs.back().id});
  writer.set_split("T+W", {seqs.front().id});
  writer.finish();
  return seqs;
}

TEST(DataRoundTrip, TwoSequencesReadBackBitIdentical) {
  TempDir dir;
  const auto written = write_dataset(dir.path(), 2);
  EXPECT_TRUE(std::filesystem::exists(dir.file("shard-00000.h5")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("shard-00001.h5")));
  const Dataset ds = Dataset::open(dir.path());
  ASSERT_EQ(ds.ids(), (std::vector<std::string>{"s0", "s1"}));
  for (const auto& seq : written) {
    const SequenceData back = ds.read_sequence(seq.id);
    expect_same(seq, back);
    ASSERT_EQ(seq.garments[1].positions.size(), back.garments[1].positions.size());
    EXPECT_EQ(0, std::memcmp(seq.garments[1].positions.data(), back.garments[1].positions.data(),
                             seq.garments[1].positions.size() * sizeof(float)));
  }
}

TEST(DataRoundTrip, FileLayoutFollowsTheFormat) {
  TempDir dir;
  write_dataset(dir.path(), 1);
  H5::H5File file(dir.file("shard-00000.h5"), H5F_ACC_RDONLY);
  H5::Group root = file.openGroup("/");
  const auto string_attr = [&](const char* name) {
    std::string text;
    const H5::Attribute attr = root.openAttribute(name);
    attr.read(attr.getStrType(), text);
    return text;
  };
  EXPECT_EQ(string_attr("format"), "layers-h5");
  EXPECT_EQ(string_attr("units"), "m");
  EXPECT_EQ(string_attr("up"), "y");
  std::int64_t value = 0;
  root.openAttribute("format_version").read(H5::PredType::NATIVE_INT64, &value);
  EXPECT_EQ(value, 1);
  root.openAttribute("fps").read(H5::PredType::NATIVE_INT64, &value);
  EXPECT_EQ(value, 30);
  for (const auto& [path, v] :
       {std::pair<std::string, hsize_t>{"/seq/s0/body/positions", 200}, {"/seq/s0/garments/1/positions", 128}}) {
    hsize_t chunk[3] = {0, 0, 0};
    ASSERT_EQ(file.openDataSet(path).getCreatePlist().getChunk(3, chunk), 3) << path;
    EXPECT_EQ(chunk[0], 1u);
    EXPECT_EQ(chunk[1], v);
    EXPECT_EQ(chunk[2], 3u);
  }
  double mass = 0.0;
  file.openGroup("/seq/s0/garments/0").openAttribute("mass").read(H5::PredType::NATIVE_DOUBLE, &mass);
  EXPECT_GT(mass, 0.19);
}

TEST(DataRoundTrip, ManifestSplitsAndInfo) {
  TempDir dir;
  const auto written = write_dataset(dir.path(), 3, 2);
  const Dataset ds = Dataset::open(dir.path());
  EXPECT_EQ(ds.manifest().name, "tiny");
  EXPECT_EQ(ds.manifest().seed, 7u);
  EXPECT_EQ(ds.manifest().n_sequences, 3);
  EXPECT_EQ(ds.manifest().n_shards, 2);
  EXPECT_EQ(ds.manifest().n_frames, 36);
  EXPECT_NE(ds.manifest().generator_yaml.find("gender: 0.5"), std::string::npos);
  EXPECT_EQ(ds.splits().names(), (std::vector<std::string>{"train", "test", "T+W"}));
  EXPECT_EQ(ds.splits().get("train"), (std::vector<std::string>{"s0", "s1"}));

  const SequenceInfo& info = ds.info("s2");
  EXPECT_EQ(info.n_frames, 12);
  EXPECT_EQ(info.body_vertices, 200);
  EXPECT_EQ(info.n_joints, 5);
  EXPECT_EQ(info.motion, written[2].motion);
  EXPECT_EQ(info.tags, written[2].tags);
  ASSERT_EQ(info.garments.size(), 2u);
  EXPECT_EQ(info.garments[1].type, "jacket");
  EXPECT_EQ(info.garments[1].layer, 1);
  EXPECT_EQ(info.garments[0].n_vertices, 128);
  EXPECT_EQ(info.garments[0].n_faces, 7 * 15 * 2);
  EXPECT_NE(info.shard.find("shard-00001.h5"), std::string::npos);
}

TEST(DataRoundTrip, ManifestMotionCountsOnlyWhenRecorded) {
  TempDir dir;
  DatasetManifest m;
  m.name = "x";
  write_manifest(dir.file("plain.yaml"), m);
  EXPECT_EQ(manifest_to_yaml(m).find("motions"), std::string::npos);
  EXPECT_EQ(read_manifest(dir.file("plain.yaml")).n_distinct_motions, -1);
  m.n_distinct_motions = 3;
  m.motion_families["procedural:walk"] = {2, 2, 1};
  m.motion_families["bvh:cmu/131_01_start_walk_stop.bvh"] = {1, 1, 0};
  write_manifest(dir.file("counted.yaml"), m);
  const DatasetManifest back = read_manifest(dir.file("counted.yaml"));
  EXPECT_EQ(back.n_distinct_motions, 3);
  ASSERT_EQ(back.motion_families.size(), 2u);
  EXPECT_EQ(back.motion_families.at("procedural:walk").sequences, 2);
  EXPECT_EQ(back.motion_families.at("procedural:walk").skipped, 1);
  EXPECT_EQ(back.motion_families.at("bvh:cmu/131_01_start_walk_stop.bvh").distinct, 1);
  // Without clean windows the frame counts are not written.
  EXPECT_EQ(manifest_to_yaml(m).find("frames_stored"), std::string::npos);
  EXPECT_EQ(back.motion_families.at("procedural:walk").frames_stored, -1);
}

TEST(DataRoundTrip, ManifestCleanWindowCountsRoundTrip) {
  TempDir dir;
  DatasetManifest m;
  m.name = "x";
  m.n_distinct_motions = 1;
  MotionFamilyCount& c = m.motion_families["procedural:squat"];
  c = {3, 1, 1};
  c.scenes = 4;
  c.cut = 2;
  c.frames_asked = 240;
  c.frames_simulated = 201;
  c.frames_stored = 150;
  c.dropped = {{"stretch", 60}, {"h_crossing_clear", 30}};
  write_manifest(dir.file("w.yaml"), m);
  const MotionFamilyCount back = read_manifest(dir.file("w.yaml")).motion_families.at("procedural:squat");
  EXPECT_EQ(back.scenes, 4);
  EXPECT_EQ(back.cut, 2);
  EXPECT_EQ(back.frames_asked, 240);
  EXPECT_EQ(back.frames_simulated, 201);
  EXPECT_EQ(back.frames_stored, 150);
  EXPECT_EQ(back.dropped, c.dropped);
  // A damaged count gets one line naming the key.
  std::string text = read_text_file(dir.file("w.yaml"));
  const auto at = text.find("stretch: 60");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 11, "stretch: lots");
  std::ofstream(dir.file("bad.yaml")) << text;
  const std::string said = test::error_of([&] { read_manifest(dir.file("bad.yaml")); });
  EXPECT_NE(said.find("motions.families.procedural:squat.dropped.stretch"), std::string::npos) << said;
}

TEST(DataRoundTrip, SingleShardFileOpensDirectly) {
  TempDir dir;
  const auto a = make_sequence("a", 1);
  auto b = make_sequence("b", 2);
  b.tags.clear();  // empty string-array attribute
  b.shape.clear();
  b.garments.pop_back();
  write_shard(dir.file("one.h5"), {a, b});
  const Dataset ds = Dataset::open(dir.file("one.h5"));
  EXPECT_EQ(ds.ids(), (std::vector<std::string>{"a", "b"}));
  EXPECT_TRUE(ds.splits().empty());
  expect_same(b, ds.read_sequence("b"));
}

TEST(DataReader, WindowsEqualSlicesOfTheFullArrays) {
  TempDir dir;
  const auto written = write_dataset(dir.path(), 2);
  const Dataset ds = Dataset::open(dir.path());
  const SequenceData& seq = written[1];
  const std::int64_t T = seq.n_frames;
  for (const auto& [start, history, horizon] :
       {std::tuple<int, int, int>{1, 1, 2}, {0, 0, 0}, {5, 2, 6}, {11, 11, 0}}) {
    const Window w = ds.read_window(seq.id, start, history, horizon);
    const std::int64_t first = start - history, n = history + horizon + 1;
    EXPECT_EQ(w.first_frame, first);
    EXPECT_EQ(w.n_frames, n);
    EXPECT_EQ(w.body.positions, testing::frames_of(seq.body.positions, T, first, n));
    EXPECT_EQ(w.body.root, testing::frames_of(seq.body.root, T, first, n));
    EXPECT_EQ(w.body.root_rot, testing::frames_of(seq.body.root_rot, T, first, n));
    EXPECT_EQ(w.body.joints, testing::frames_of(seq.body.joints, T, first, n));
    EXPECT_EQ(w.wind.rotation, testing::frames_of(seq.wind.rotation, T, first, n));
    EXPECT_EQ(w.wind.strength, testing::frames_of(seq.wind.strength, T, first, n));
    ASSERT_EQ(w.garments.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
      EXPECT_EQ(w.garments[k], testing::frames_of(seq.garments[k].positions, T, first, n));
    }
  }
  const auto statics = ds.statics(seq.id);
  EXPECT_EQ(statics->body.faces, seq.body.faces);
  EXPECT_EQ(statics->garments[1].uv, seq.garments[1].uv);
  EXPECT_EQ(statics->garments[0].attributes, seq.garments[0].attributes);
}

TEST(DataReader, WindowOutOfRangeNamesSequenceAndRanges) {
  TempDir dir;
  write_dataset(dir.path(), 2);
  const Dataset ds = Dataset::open(dir.path());
  const std::string before = test::error_of<InputError>([&] { ds.read_window("s1", 0, 1, 2); });
  EXPECT_NE(before.find("/seq/s1"), std::string::npos) << before;
  EXPECT_NE(before.find("expected frames within [0,11]"), std::string::npos) << before;
  EXPECT_NE(before.find("got frames [-1,2]"), std::string::npos) << before;
  const std::string after = test::error_of<InputError>([&] { ds.read_window("s1", 10, 1, 2); });
  EXPECT_NE(after.find("got frames [9,12]"), std::string::npos) << after;
  const std::string frames = test::error_of<InputError>([&] { ds.read_frames("s0", 12, 1); });
  EXPECT_NE(frames.find("frames [12,12]"), std::string::npos) << frames;
  const std::string unknown = test::error_of<InputError>([&] { ds.statics("nope"); });
  EXPECT_NE(unknown.find("'nope'"), std::string::npos) << unknown;
}

TEST(DataReader, StaticsCacheStaysWithinItsBudget) {
  TempDir dir;
  write_dataset(dir.path(), 4, 4);
  ReaderOptions options;
  const std::size_t one = [&] { return Dataset::open(dir.path()).statics("s0")->bytes(); }();
  options.cache_bytes = one * 2 + one / 2;  // room for two
  const Dataset ds = Dataset::open(dir.path(), options);
  for (const char* id : {"s0", "s1", "s2", "s3", "s0"}) ds.statics(id);
  const CacheStats stats = ds.cache_stats();
  EXPECT_LE(stats.bytes, options.cache_bytes);
  EXPECT_EQ(stats.entries, 2u);
  EXPECT_EQ(stats.misses, 5u);  // s0 was evicted before it came back
  ds.statics("s0");
  EXPECT_EQ(ds.cache_stats().hits, 1u);
}

TEST(DataReader, ThreadsShareOneReader) {
  TempDir dir;
  const auto written = write_dataset(dir.path(), 3);
  ReaderOptions options;
  options.max_open_files = 1;  // forces handle churn between threads
  const Dataset ds = Dataset::open(dir.path(), options);
  std::vector<std::thread> threads;
  std::vector<int> failures(4, 0);
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < 30; ++i) {
        const SequenceData& seq = written[(t + i) % 3];
        const int start = 1 + (i % 9);
        const Window w = ds.read_window(seq.id, start, 1, 2);
        if (w.garments[0] != testing::frames_of(seq.garments[0].positions, seq.n_frames, start - 1, 4)) ++failures[t];
        if (ds.statics(seq.id)->body.faces != seq.body.faces) ++failures[t];
      }
    });
  }
  for (auto& th : threads) th.join();
  for (int f : failures) EXPECT_EQ(f, 0);
  EXPECT_LE(ds.cache_stats().open_files, 1u);
}

TEST(DataWriter, FailedWriteLeavesPreviousFileIntact) {
  TempDir dir;
  const std::string path = dir.file("shard-00000.h5");
  const auto good = make_sequence("good", 1);
  write_shard(path, {good});
  const std::string before = testing::read_text(path);

  auto bad = make_sequence("bad", 2);
  bad.garments[0].positions.pop_back();
  const std::string message = test::error_of<InputError>([&] { write_shard(path, {make_sequence("other", 3), bad}); });
  EXPECT_NE(message.find("/seq/bad/garments/0/positions"), std::string::npos) << message;
  EXPECT_EQ(testing::read_text(path), before);
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
  expect_same(good, Dataset::open(path).read_sequence("good"));
}

TEST(DataWriter, RejectsInconsistentSequencesWithPreciseMessages) {
  TempDir dir;
  auto seq = make_sequence("x", 1);
  seq.body.skin_index.resize(seq.body.skin_index.size() - 4);  // one body vertex short
  std::string message = test::error_of<InputError>([&] { check_sequence(seq, "out.h5"); });
  EXPECT_NE(message.find("/seq/x/body/skin_index"), std::string::npos) << message;
  EXPECT_NE(message.find("Vb=200"), std::string::npos) << message;

  seq = make_sequence("x", 1);
  seq.garments[1].faces[5] = 100000;
  message = test::error_of<InputError>([&] { check_sequence(seq, "out.h5"); });
  EXPECT_NE(message.find("/seq/x/garments/1/faces"), std::string::npos) << message;
  EXPECT_NE(message.find("100000"), std::string::npos) << message;

  // Every index rule of the schema: body skin indices below J, a joint
  // hierarchy without self-parents, panels not negative, UV faces below U.
  seq = make_sequence("x", 1);
  ASSERT_FALSE(seq.body.skin_index.empty());
  seq.body.skin_index[2] = 100000;
  message = test::error_of<InputError>([&] { check_sequence(seq, "out.h5"); });
  EXPECT_NE(message.find("/seq/x/body/skin_index"), std::string::npos) << message;
  seq = make_sequence("x", 1);
  ASSERT_GT(seq.body.joint_parents.size(), 1u);
  seq.body.joint_parents[1] = 1;
  message = test::error_of<InputError>([&] { check_sequence(seq, "out.h5"); });
  EXPECT_NE(message.find("/seq/x/body/joint_parents"), std::string::npos) << message;
  EXPECT_NE(message.find("own parent"), std::string::npos) << message;
  seq = make_sequence("x", 1);
  seq.garments[0].panel[0] = -1;
  message = test::error_of<InputError>([&] { check_sequence(seq, "out.h5"); });
  EXPECT_NE(message.find("/seq/x/garments/0/panel"), std::string::npos) << message;
  seq = make_sequence("x", 1);
  seq.garments[0].uv_faces[0] = static_cast<std::int32_t>(seq.garments[0].uv.size() / 2);
  message = test::error_of<InputError>([&] { check_sequence(seq, "out.h5"); });
  EXPECT_NE(message.find("/seq/x/garments/0/uv_faces"), std::string::npos) << message;

  seq = make_sequence("x", 1);
  seq.garments[0].type = "cape";
  message = test::error_of<InputError>([&] { check_sequence(seq, "out.h5"); });
  EXPECT_NE(message.find("'cape'"), std::string::npos) << message;

  seq = make_sequence("x/y", 1);
  EXPECT_NE(test::error_of<InputError>([&] { check_sequence(seq, "out.h5"); }).find("no '/'"), std::string::npos);

  DatasetWriter writer(dir.path());
  writer.add(make_sequence("a", 1));
  EXPECT_NE(test::error_of<InputError>([&] { writer.add(make_sequence("a", 2)); }).find("duplicate"),
            std::string::npos);
  writer.set_split("train", {"a", "ghost"});
  message = test::error_of<InputError>([&] { writer.finish(); });
  EXPECT_NE(message.find("'ghost'"), std::string::npos) << message;
}

TEST(DataWriter, ResumeKeepsFinishedShards) {
  TempDir dir;
  {
    DatasetWriterOptions options;
    options.sequences_per_shard = 2;
    DatasetWriter writer(dir.path(), options);
    for (int i = 0; i < 3; ++i) writer.add(make_sequence("s" + std::to_string(i), i));
    // Interrupted: s2 sits in an uncommitted shard and is lost.
  }
  EXPECT_TRUE(std::filesystem::exists(dir.file("shard-00000.h5")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("shard-00001.h5")));
  EXPECT_NE(test::error_of<InputError>([&] { DatasetWriter again(dir.path()); }).find("resume"), std::string::npos);

  DatasetWriterOptions options;
  options.sequences_per_shard = 2;
  options.resume = true;
  DatasetWriter writer(dir.path(), options);
  EXPECT_TRUE(writer.contains("s0"));
  EXPECT_TRUE(writer.contains("s1"));
  EXPECT_FALSE(writer.contains("s2"));
  writer.add(make_sequence("s2", 2));
  writer.set_split("train", {"s0", "s1", "s2"});
  writer.finish();
  const Dataset ds = Dataset::open(dir.path());
  EXPECT_EQ(ds.ids(), (std::vector<std::string>{"s0", "s1", "s2"}));
  EXPECT_EQ(ds.manifest().n_shards, 2);
  EXPECT_EQ(ds.manifest().n_frames, 36);
}

// Every numeric dataset carries a Fletcher32 checksum per chunk: bytes
// flipped inside the body positions (to values that are still finite
// floats) make the read fail with the file and the object named, instead of
// returning garbage.
TEST(DataChecksums, FlippedBytesInAShardAreRefused) {
  TempDir dir;
  auto seq = make_sequence("s", 3);
  for (float& v : seq.body.positions) v = 0.625f;  // a pattern to find in the file
  write_shard(dir.file("one.h5"), {seq});
  std::string bytes = testing::read_text(dir.file("one.h5"));
  const float pattern[4] = {0.625f, 0.625f, 0.625f, 0.625f};
  const std::size_t at = bytes.find(std::string(reinterpret_cast<const char*>(pattern), sizeof pattern));
  ASSERT_NE(at, std::string::npos);
  for (std::size_t i = at; i < at + 16; i += 4) bytes[i + 3] = 0x7e;  // 0.625 -> about 1.3e38
  testing::write_text(dir.file("one.h5"), bytes);
  const Dataset ds = Dataset::open(dir.file("one.h5"));
  const std::string message = layers::test::error_of([&] { ds.read_sequence("s"); });
  EXPECT_NE(message.find(dir.file("one.h5")), std::string::npos) << message;
  EXPECT_NE(message.find("body/positions"), std::string::npos) << message;
  EXPECT_NE(message.find("checksum"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

}  // namespace
}  // namespace layers::data
