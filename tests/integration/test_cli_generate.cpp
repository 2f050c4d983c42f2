// `layers generate` end to end on a very small config: shards, resume,
// determinism, the dataset files, config mismatch on resume, and the
// batch-scheduler path (--shard auto from the environment, --no-finalize,
// then --finalize). The
// validation thresholds are opened wide here: these tests are about the
// pipeline; the physics checks live in the sim and generator tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "layers/core/atomic_file.h"
#include "layers/core/config_node.h"
#include "layers/core/text_file.h"
#include "layers/data/dataset.h"
#include "run_command.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;
using test::run_command;

namespace {

std::string generate(const std::string& out, const std::string& extra = "") {
  return test::layers_bin() + " generate --config " + test::source_dir() + "/configs/data/tiny.yaml --out " + out +
         " --quiet --set sequences=3 --set frames=6 --set drape_frames=3 --set body.transition_frames=3"
         " --set sequences_per_shard=2 --set garments.fit.edge_length=0.08"
         " --set sim.validation.max_l_penetration=1 --set sim.validation.max_h_penetration=1"
         " --set sim.validation.max_stretch=100 --set sim.validation.max_h_crossing_clear=1 " +
         extra;
}

std::string bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(CliGenerate, ShardsThenCompleteDatasetThatValidates) {
  test::TempDir dir;
  const std::string out = dir.file("ds");
  auto first = run_command(generate(out, "--shard 1/2"));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("1 scenes in shard 1/2: 1 simulated now"), std::string::npos) << first.output;
  EXPECT_NE(first.output.find("dataset not complete yet"), std::string::npos) << first.output;
  EXPECT_TRUE(fs::exists(out + "/shard-00001.h5"));
  EXPECT_FALSE(fs::exists(out + "/dataset.yaml"));

  auto second = run_command(generate(out, "--shard 0/2 --threads 2"));
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("2 scenes in shard 0/2: 2 simulated now"), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("dataset complete"), std::string::npos) << second.output;
  for (const char* f : {"dataset.yaml", "splits.yaml", "stats.h5", "generator.yaml", "shard-00000.h5"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  EXPECT_FALSE(fs::exists(out + "/parts"));

  auto valid = run_command(test::layers_bin() + " validate " + out);
  EXPECT_EQ(valid.exit_code, 0) << valid.output;
  auto info = run_command(test::layers_bin() + " info " + out);
  EXPECT_NE(info.output.find("sequences 3  frames 18"), std::string::npos) << info.output;
  // The manifest names the code that simulated the scenes: this build's
  // revision, as `layers --version` prints it.
  auto version = run_command(test::layers_bin() + " --version");
  ASSERT_EQ(version.exit_code, 0) << version.output;
  ASSERT_EQ(version.output.rfind("layers ", 0), 0u) << version.output;
  std::string revision = version.output.substr(7);
  while (!revision.empty() && revision.back() == '\n') revision.pop_back();
  EXPECT_FALSE(revision.empty());
  EXPECT_NE(bytes(out + "/dataset.yaml").find("generator_revision: " + revision), std::string::npos);
  EXPECT_NE(info.output.find("generator " + revision), std::string::npos) << info.output;
  const std::string splits = bytes(out + "/splits.yaml");
  for (const char* key : {"train:", "val:", "test:", "T:", "T+W:", "L:", "L+W:"})
    EXPECT_NE(splits.find(key), std::string::npos) << key << " in " << splits;

  // The validation measures recomputed from the stored frames: one line per
  // sequence, their spread and the totals; the exit code follows the count
  // over the (default) thresholds.
  auto physics = run_command(test::layers_bin() + " validate --physics " + out);
  EXPECT_NE(physics.output.find("3 sequences, 18 frames: mean H-penetration"), std::string::npos) << physics.output;
  EXPECT_NE(physics.output.find("0 non-finite values"), std::string::npos) << physics.output;
  // Below the table: the spread over the sequences and the crossing target.
  EXPECT_NE(physics.output.find("spread over 3 sequences:"), std::string::npos) << physics.output;
  EXPECT_NE(physics.output.find("crossing target 0.10%: frames with H-crossing within it"), std::string::npos)
      << physics.output;
  EXPECT_NE(physics.output.find(" of 18 ("), std::string::npos) << physics.output;
  for (const char* id : {"seq-000000", "seq-000001", "seq-000002"})
    EXPECT_NE(physics.output.find(id), std::string::npos) << id;
  const bool clean = physics.output.find("; 0 over the thresholds") != std::string::npos;
  EXPECT_EQ(physics.exit_code, clean ? 0 : 1) << physics.output;

  // Every frame's measures as a table: a header and one row per sequence
  // and frame, in the order of the dataset.
  const std::string csv = dir.file("frames.csv");
  auto rows = run_command(test::layers_bin() + " validate --physics " + out + " --frames-csv " + csv);
  EXPECT_EQ(rows.exit_code, physics.exit_code) << rows.output;
  std::ifstream in(csv);
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line.rfind("sequence,frame,h_penetration_pct,", 0), 0u) << line;
  int count = 0;
  std::vector<std::string> seen;
  while (std::getline(in, line)) {
    ++count;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 15) << line;
    const std::string id = line.substr(0, line.find(','));
    // Column 8, cloth_crossing_pairs: the collision pass leaves none.
    std::string field = line;
    for (int k = 0; k < 7; ++k) field = field.substr(field.find(',') + 1);
    EXPECT_EQ(field.substr(0, field.find(',')), "0") << line;
    if (seen.empty() || seen.back() != id) seen.push_back(id);
  }
  EXPECT_EQ(count, 18);
  EXPECT_EQ(seen, (std::vector<std::string>{"seq-000000", "seq-000001", "seq-000002"}));
  // Measured on two threads: the same report and the same table.
  auto two = run_command(test::layers_bin() + " validate --physics " + out + " --threads 2 --frames-csv " +
                         dir.file("frames2.csv"));
  EXPECT_EQ(two.exit_code, rows.exit_code) << two.output;
  EXPECT_EQ(two.output.substr(0, two.output.rfind("per-frame measures:")),
            rows.output.substr(0, rows.output.rfind("per-frame measures:")));
  EXPECT_EQ(bytes(dir.file("frames2.csv")), bytes(csv));
  // The file is the user's now: asked again, validate refuses and keeps it.
  const std::string kept = bytes(csv);
  auto again = run_command(test::layers_bin() + " validate --physics " + out + " --frames-csv " + csv);
  EXPECT_EQ(again.exit_code, 1) << again.output;
  EXPECT_NE(again.output.find("--frames-csv must name a new file"), std::string::npos) << again.output;
  EXPECT_EQ(again.output.find("valid LAYERS-H5"), std::string::npos) << "refused before any work: " << again.output;
  EXPECT_EQ(bytes(csv), kept);
  auto no_physics = run_command(test::layers_bin() + " validate " + out + " --frames-csv " + dir.file("other.csv"));
  EXPECT_EQ(no_physics.exit_code, 2) << no_physics.output;
  EXPECT_NE(no_physics.output.find("--frames-csv needs --physics"), std::string::npos) << no_physics.output;
  EXPECT_FALSE(fs::exists(dir.file("other.csv")));
  auto threads_alone = run_command(test::layers_bin() + " validate " + out + " --threads 2");
  EXPECT_EQ(threads_alone.exit_code, 2) << threads_alone.output;
  EXPECT_NE(threads_alone.output.find("--threads needs --physics"), std::string::npos) << threads_alone.output;
}

TEST(CliGenerate, SameSeedSameBytesAndResumeRedoesOnlyWhatIsMissing) {
  test::TempDir dir;
  auto a = run_command(generate(dir.file("a")));
  ASSERT_EQ(a.exit_code, 0) << a.output;
  auto b = run_command(generate(dir.file("b"), "--threads 2"));
  ASSERT_EQ(b.exit_code, 0) << b.output;
  for (const char* f : {"shard-00000.h5", "shard-00001.h5", "stats.h5", "splits.yaml", "dataset.yaml"})
    EXPECT_EQ(bytes(dir.file(std::string("a/") + f)), bytes(dir.file(std::string("b/") + f))) << f;

  // A finished dataset is kept; a removed shard is made again, identically.
  auto again = run_command(generate(dir.file("a")));
  EXPECT_NE(again.output.find("0 simulated now (0 written, 0 skipped), 3 finished before"), std::string::npos)
      << again.output;
  const std::string shard1 = bytes(dir.file("a/shard-00001.h5"));
  fs::remove(dir.file("a/shard-00001.h5"));
  auto resumed = run_command(generate(dir.file("a")));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("1 simulated now"), std::string::npos) << resumed.output;
  EXPECT_EQ(bytes(dir.file("a/shard-00001.h5")), shard1);

  // The attribute-to-material map is the config's: another one makes other frames.
  auto stiffer = run_command(generate(dir.file("c"), "--set garments.material.compression_per_stiffness=20"));
  ASSERT_EQ(stiffer.exit_code, 0) << stiffer.output;
  const auto positions = [&](const std::string& folder) {
    const data::Dataset ds = data::Dataset::open(dir.file(folder));
    if (ds.ids().empty()) return std::vector<float>{};
    return ds.read_sequence(ds.ids().front()).garments.front().positions;
  };
  const std::vector<float> as_shipped = positions("a"), stiffer_frames = positions("c");
  ASSERT_FALSE(as_shipped.empty());
  ASSERT_EQ(as_shipped.size(), stiffer_frames.size());
  EXPECT_NE(as_shipped, stiffer_frames);
}

TEST(CliGenerate, BadConfigAndMismatchedResume) {
  test::TempDir dir;
  auto ok = run_command(generate(dir.file("ds")));
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  auto other = run_command(generate(dir.file("ds"), "--set seed=99"));
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_NE(other.output.find("different generator config"), std::string::npos) << other.output;

  auto outfit = run_command(generate(dir.file("x"), "--set 'garments.outfits=[{inner: [jacket]}]'"));
  EXPECT_EQ(outfit.exit_code, 1) << outfit.output;
  EXPECT_NE(outfit.output.find("garments.outfits[0].inner"), std::string::npos) << outfit.output;
  auto shard = run_command(generate(dir.file("x"), "--shard 2/2"));
  EXPECT_EQ(shard.exit_code, 2) << shard.output;  // a flag value out of its range: usage
  EXPECT_NE(shard.output.find("--shard"), std::string::npos) << shard.output;
  auto unknown = run_command(generate(dir.file("x"), "--set sim.substep=3"));
  EXPECT_EQ(unknown.exit_code, 1) << unknown.output;
  EXPECT_NE(unknown.output.find("sim.substep"), std::string::npos) << unknown.output;
}

// What an array job does: each task picks its shard from the scheduler's
// environment and leaves the dataset files alone; --finalize refuses while
// a shard is missing, then writes them. The result is the same bytes as
// one process's run.
TEST(CliGenerate, SchedulerShardsThenFinalizeMatchOneRun) {
  test::TempDir dir;
  auto one = run_command(generate(dir.file("one")));
  ASSERT_EQ(one.exit_code, 0) << one.output;

  const std::string out = dir.file("arr");
  const std::string finalize = generate(out, "--finalize");
  auto nothing = run_command(finalize);  // no run started this folder
  EXPECT_EQ(nothing.exit_code, 1) << nothing.output;
  EXPECT_NE(nothing.output.find("generator.yaml: not found"), std::string::npos) << nothing.output;
  EXPECT_FALSE(fs::exists(out + "/dataset.yaml"));

  auto slurm = run_command(
      "env -u JOB_COMPLETION_INDEX -u LAYERS_SHARD_COUNT SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=2 "
      "SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=1 " +
      generate(out, "--shard auto --no-finalize"));
  ASSERT_EQ(slurm.exit_code, 0) << slurm.output;
  EXPECT_NE(slurm.output.find("1 scenes in shard 1/2: 1 simulated now"), std::string::npos) << slurm.output;
  EXPECT_NE(slurm.output.find("not finalized (--no-finalize)"), std::string::npos) << slurm.output;
  auto missing = run_command(finalize);
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_NE(missing.output.find(out + ": shards missing: 0 (of 2)"), std::string::npos) << missing.output;
  EXPECT_FALSE(fs::exists(out + "/dataset.yaml"));

  auto k8s = run_command("env -u SLURM_ARRAY_TASK_ID JOB_COMPLETION_INDEX=0 LAYERS_SHARD_COUNT=2 " +
                         generate(out, "--shard auto --no-finalize --threads 2"));
  ASSERT_EQ(k8s.exit_code, 0) << k8s.output;
  EXPECT_NE(k8s.output.find("2 scenes in shard 0/2: 2 simulated now"), std::string::npos) << k8s.output;
  EXPECT_FALSE(fs::exists(out + "/dataset.yaml"));
  EXPECT_FALSE(fs::exists(out + "/stats.h5"));

  auto other = run_command(generate(out, "--finalize --set seed=7"));
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_NE(other.output.find("different generator config"), std::string::npos) << other.output;
  // Scenes of another generator revision are never mixed into this one's.
  const std::string revision = bytes(out + "/generator_revision");
  write_text_atomic(out + "/generator_revision", "0123456789ab\n");
  auto mixed = run_command(finalize);
  EXPECT_EQ(mixed.exit_code, 1) << mixed.output;
  EXPECT_NE(mixed.output.find("started by the generator of revision 0123456789ab"), std::string::npos) << mixed.output;
  EXPECT_FALSE(fs::exists(out + "/dataset.yaml"));
  write_text_atomic(out + "/generator_revision", revision);
  auto done = run_command(finalize);
  ASSERT_EQ(done.exit_code, 0) << done.output;
  EXPECT_NE(done.output.find("dataset complete: 2 shards, 3 sequences, 18 frames"), std::string::npos) << done.output;
  for (const char* f :
       {"shard-00000.h5", "shard-00001.h5", "stats.h5", "splits.yaml", "dataset.yaml", "generator.yaml"})
    EXPECT_EQ(bytes(dir.file(std::string("one/") + f)), bytes(out + "/" + f)) << f;
  EXPECT_FALSE(fs::exists(out + "/parts"));
  auto again = run_command(finalize);  // the same bytes again
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(bytes(dir.file("one/dataset.yaml")), bytes(out + "/dataset.yaml"));

  // A run stopped after its shard's last scene but before merging it:
  // --finalize merges the finished parts (shard 1 is the one scene
  // seq-000002, so its part holds what the shard holds).
  const std::string shard1 = bytes(out + "/shard-00001.h5");
  fs::remove(out + "/shard-00001.h5");
  fs::create_directories(out + "/parts");
  fs::copy_file(dir.file("one/shard-00001.h5"), out + "/parts/seq-000002.h5");
  auto merged = run_command(finalize);
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  EXPECT_EQ(bytes(out + "/shard-00001.h5"), shard1);
  EXPECT_FALSE(fs::exists(out + "/parts"));
  EXPECT_EQ(run_command(test::layers_bin() + " validate " + out).exit_code, 0);
}

TEST(CliGenerate, BadShardUsage) {
  test::TempDir dir;
  const std::string out = dir.file("x");
  auto none = run_command("env -u SLURM_ARRAY_TASK_ID -u JOB_COMPLETION_INDEX " + generate(out, "--shard auto"));
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("--shard auto: expected SLURM_ARRAY_TASK_ID"), std::string::npos) << none.output;
  auto beyond = run_command("env -u SLURM_ARRAY_TASK_ID JOB_COMPLETION_INDEX=4 " + generate(out, "--shard auto/3"));
  EXPECT_EQ(beyond.exit_code, 2) << beyond.output;
  EXPECT_NE(beyond.output.find("JOB_COMPLETION_INDEX: expected a shard index below the count 3"), std::string::npos)
      << beyond.output;
  auto both = run_command(generate(out, "--finalize --shard 0/2"));
  EXPECT_EQ(both.exit_code, 2) << both.output;
  EXPECT_NE(both.output.find("excludes"), std::string::npos) << both.output;
  EXPECT_FALSE(fs::exists(out)) << "a usage error must not start the folder";
}

// The Kubernetes manifests (scripts/k8s) run for real minus Kubernetes:
// each pod's exact command and arguments, with the environment an Indexed
// Job gives pod k (JOB_COMPLETION_INDEX=k and the manifest's env), the
// image's paths mapped onto this checkout and a temporary volume.
namespace {

struct Pod {
  std::string command;  // shell words, paths mapped
  std::string env;      // "NAME=value " pairs from the manifest
  const cfg::Node* spec = nullptr;
};

Pod read_pod(const cfg::Node& job, const std::string& volume) {
  const cfg::Node* containers = job.find("spec")->find("template")->find("spec")->find("containers");
  EXPECT_TRUE(containers && containers->seq.size() == 1);
  const cfg::Node& c = containers->seq.at(0);
  Pod pod;
  pod.spec = job.find("spec");
  auto map_path = [&](std::string word) {
    const std::string image_configs = "/opt/layers/share/layers/configs/";
    if (word.rfind(image_configs, 0) == 0) return test::source_dir() + "/configs/" + word.substr(image_configs.size());
    if (word.rfind("/data/", 0) == 0) return volume + word.substr(5);
    return word;
  };
  std::vector<std::string> words;
  for (const auto& w : c.find("command")->seq) words.push_back(w.scalar);
  EXPECT_EQ(words.at(0), "layers");
  words[0] = test::layers_bin();
  for (const auto& w : c.find("args")->seq) words.push_back(map_path(w.scalar));
  for (const auto& w : words) pod.command += "'" + w + "' ";
  if (const cfg::Node* env = c.find("env"))
    for (const auto& e : env->seq) pod.env += e.find("name")->scalar + "=" + e.find("value")->scalar + " ";
  return pod;
}

}  // namespace

TEST(CliGenerate, KubernetesIndexedJobManifestsMakeTheDataset) {
  test::TempDir dir;
  const std::string k8s = test::source_dir() + "/scripts/k8s/";
  const cfg::Node gen_job = cfg::parse(read_text_file(k8s + "generate-job.yaml"), "generate-job.yaml");
  const cfg::Node fin_job = cfg::parse(read_text_file(k8s + "finalize-job.yaml"), "finalize-job.yaml");
  const Pod gen = read_pod(gen_job, dir.path()), fin = read_pod(fin_job, dir.path());
  ASSERT_EQ(gen.spec->find("completionMode")->scalar, "Indexed");
  const int completions = std::stoi(gen.spec->find("completions")->scalar);
  EXPECT_NE(gen.env.find("LAYERS_SHARD_COUNT=" + std::to_string(completions) + " "), std::string::npos)
      << "LAYERS_SHARD_COUNT must equal completions: " << gen.env;
  EXPECT_NE(gen.command.find("'--shard' 'auto'"), std::string::npos) << gen.command;
  // The finalize pod names the same config, settings and folder.
  const std::string same = gen.command.substr(0, gen.command.find("'--shard'"));
  EXPECT_EQ(fin.command, same + "'--finalize' ") << fin.command;

  auto pod = [&](int k) {
    return "env -u SLURM_ARRAY_TASK_ID JOB_COMPLETION_INDEX=" + std::to_string(k) + " " + gen.env + gen.command;
  };
  // All pods but the last, at once; the finalize Job applied too early fails.
  std::string some = "status=0; pids=; ";
  for (int k = 0; k + 1 < completions; ++k) some += pod(k) + " & pids=\"$pids $!\"; ";
  auto first = run_command("(" + some + "for p in $pids; do wait $p || status=1; done; exit $status)");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  auto early = run_command(fin.env + fin.command);
  EXPECT_EQ(early.exit_code, 1) << early.output;
  EXPECT_NE(early.output.find("shards missing: " + std::to_string(completions - 1) + " (of " +
                              std::to_string(completions) + ")"),
            std::string::npos)
      << early.output;
  auto last = run_command(pod(completions - 1));
  ASSERT_EQ(last.exit_code, 0) << last.output;
  EXPECT_FALSE(fs::exists(dir.file("tiny/dataset.yaml"))) << "pods must leave finalizing to the finalize Job";
  auto done = run_command(fin.env + fin.command);
  ASSERT_EQ(done.exit_code, 0) << done.output;
  EXPECT_NE(done.output.find("dataset complete: " + std::to_string(completions) + " shards"), std::string::npos)
      << done.output;
  auto valid = run_command(test::layers_bin() + " validate " + dir.file("tiny"));
  EXPECT_EQ(valid.exit_code, 0) << valid.output;
}

// `layers run` makes its dataset with the generator when the folder is
// missing, finds it complete the second time (the generator's own
// completeness check), and refuses a folder made with other settings.
TEST(CliRun, StudyGeneratesItsDatasetOnceThenReusesIt) {
  test::TempDir dir;
  const std::string src = test::source_dir();
  const std::string study = dir.write(
      "study.yaml",
      "name: st\noutput: " + dir.file("runs") + "\ndataset:\n  config: " + src +
          "/configs/data/tiny.yaml\n  folder: " + dir.file("data") +
          "\n  set: [sequences=3, frames=4, drape_frames=2, body.transition_frames=2, sequences_per_shard=3,"
          " garments.fit.edge_length=0.1, sim.validation.max_l_penetration=1, sim.validation.max_h_penetration=1,"
          " sim.validation.max_stretch=100, sim.validation.max_h_crossing_clear=1]\nsteps: [train, "
          "eval]\nexperiments:\n  - {name: static, file: " +
          src + "/configs/experiments/static_tiny.yaml}\n");
  auto first = run_command(test::layers_bin() + " run " + study);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("3 scenes simulated (3 written, 0 skipped)"), std::string::npos) << first.output;
  EXPECT_TRUE(fs::exists(dir.file("runs/static/eval-test/metrics.json")));
  auto second = run_command(test::layers_bin() + " run " + study);
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("0 steps ran"), std::string::npos) << second.output;
  auto other = run_command(test::layers_bin() + " run " + study + " --set \"dataset.set=[sequences=3, frames=5]\"");
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_NE(other.output.find("made with another generator config"), std::string::npos) << other.output;

  // Two runs in two lanes: each a child `layers run --only`, its output in
  // its run's lane.log; this process then finds them current and reports.
  const std::string lanes = dir.write(
      "lanes.yaml", "name: lanes\noutput: " + dir.file("lane-runs") + "\ndataset:\n  config: " + src +
                        "/configs/data/tiny.yaml\n  folder: " + dir.file("data") +
                        "\n  set: [sequences=3, frames=4, drape_frames=2, body.transition_frames=2, "
                        "sequences_per_shard=3, garments.fit.edge_length=0.1, sim.validation.max_l_penetration=1, "
                        "sim.validation.max_h_penetration=1, sim.validation.max_stretch=100, "
                        "sim.validation.max_h_crossing_clear=1]\nsteps: [train, eval, "
                        "report]\nexperiments:\n  - {name: static, file: " +
                        src + "/configs/experiments/static_tiny.yaml}\n  - {name: skinned, file: " + src +
                        "/configs/experiments/skinned_tiny.yaml}\n");
  auto laned = run_command(test::layers_bin() + " run " + lanes + " --lanes 2");
  ASSERT_EQ(laned.exit_code, 0) << laned.output;
  EXPECT_NE(laned.output.find("2 runs in 2 lanes"), std::string::npos) << laned.output;
  for (const char* run : {"static", "skinned"}) {
    const std::string log = read_text_file(dir.file(std::string("lane-runs/") + run + "/lane.log"));
    EXPECT_NE(log.find("eval-test: done"), std::string::npos) << log;
    EXPECT_TRUE(fs::exists(dir.file(std::string("lane-runs/") + run + "/eval-test/metrics.json")));
  }
  EXPECT_EQ(laned.output.find("eval-test: running"), std::string::npos) << laned.output;  // not here
  EXPECT_TRUE(fs::exists(dir.file("lane-runs/report/report.md")));
}
