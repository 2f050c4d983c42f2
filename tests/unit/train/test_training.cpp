// Checkpoints, rollouts, the trainer and the evaluator on a synthetic
// dataset with the tiny test model.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <ATen/Parallel.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "layers/core/error.h"
#include "layers/core/source_revision.h"
#include "layers/core/text_file.h"
#include "layers/data/run_layout.h"
#include "layers/report/report.h"
#include "layers/train/checkpoint.h"
#include "layers/train/compute_threads.h"
#include "layers/train/evaluator.h"
#include "layers/train/session.h"
#include "layers/train/trainer.h"
#include "temp_dir.h"
#include "train_fixture.h"

namespace layers::train {
namespace {

// A frame's value of a registered metric, and the ground truth's.
const metrics::FrameValue& value_of(const FrameMetrics& m, const std::string& key) {
  return m.value.at(metrics::index_of(key));
}
double truth_of(const FrameMetrics& m, const std::string& key) { return m.truth.at(metrics::index_of(key)); }

struct Fixture : ::testing::Test {
  test::TempDir dir;
  zoo::Registry registry;
  std::string dataset;
  void SetUp() override {
    testing::register_test_models(registry);
    dataset = testing::write_dataset(dir.path() + "/data", 5, 12);
  }
  ExperimentConfig config(const std::string& run, const std::string& model = "tiny") {
    return testing::experiment(dataset, dir.path() + "/" + run, model);
  }
  TrainOptions quiet() {
    TrainOptions o;
    o.progress = false;
    return o;
  }
  // The tiny model trained one epoch as run `run`, then evaluated on the test split.
  EvalReport trained_and_evaluated(const std::string& run) {
    ExperimentConfig c = config(run);
    c.train.epochs = 1;
    run_training(c, registry, quiet());
    EvalOptions o;
    o.progress = false;
    return run_evaluation(c, registry, o);
  }
};

at::Tensor params_of(const ExperimentConfig& c, zoo::Registry& registry) {
  Session s = open_session(c, registry);
  load_checkpoint(checkpoint_path(c, "last"), *s.model, nullptr);
  std::vector<at::Tensor> all;
  for (const at::Tensor& p : s.model->parameters()) all.push_back(p.detach().flatten());
  return at::cat(all);
}

TEST_F(Fixture, RunThreadsReachTorchAndOpenBlas) {
  // run.threads must bound OpenBLAS's pool too: torch's setting alone
  // leaves it at one thread per core.
  // With two threads, the matrix products get them and torch's own pool
  // one (both pools at two threads oversubscribe two cores).
  ExperimentConfig c = config("threads");
  c.run.threads = 2;
  open_session(c, registry);
  if (blas_threads() < 0) GTEST_SKIP() << "the loaded BLAS is not OpenBLAS";
  EXPECT_EQ(blas_threads(), 2);
  EXPECT_EQ(at::get_num_threads(), 1);
  c.run.threads = 1;
  open_session(c, registry);
  EXPECT_EQ(at::get_num_threads(), 1);
  EXPECT_EQ(blas_threads(), 1);
}

TEST_F(Fixture, TrainingLowersTheLossAndValidates) {
  ExperimentConfig c = config("run");
  c.train.epochs = 6;
  c.train.lr = 0.05;
  c.train.curriculum_max = 0;  // same task every epoch: losses comparable
  const TrainReport r = run_training(c, registry, quiet());
  ASSERT_EQ(r.epochs.size(), 6u);
  EXPECT_EQ(r.trainable_parameters, 4);
  EXPECT_LT(r.epochs.back().loss, 0.1 * r.epochs.front().loss);
  EXPECT_GT(r.epochs.back().val_error_mm, 0.0);
  EXPECT_LT(r.epochs.back().val_error_mm, 50.0);  // a few mm per frame of drift at most
  EXPECT_DOUBLE_EQ(r.epochs[2].lr, 0.05 * 0.5);   // halved every 2 epochs
  EXPECT_TRUE(std::filesystem::exists(r.last_checkpoint));
  EXPECT_TRUE(std::filesystem::exists(r.best_checkpoint));
}

// train.patience: with learning rate 0 every epoch validates the same
// model, so no epoch after the first has a lower error: patience 2 stops
// after epoch 3 of 6, the selection record says so, and resuming the run
// with more epochs trains none.
TEST_F(Fixture, PatienceStopsWhenValidationNoLongerImproves) {
  ExperimentConfig c = config("patience");
  c.train.epochs = 6;
  c.train.lr = 0;
  c.train.curriculum_max = 0;
  c.train.patience = 2;
  const TrainReport r = run_training(c, registry, quiet());
  EXPECT_EQ(r.epochs_done, 3);
  ASSERT_EQ(r.epochs.size(), 3u);
  EXPECT_DOUBLE_EQ(r.epochs[1].val_error_mm, r.epochs[0].val_error_mm);
  const nlohmann::json sel = nlohmann::json::parse(
      read_text_file((std::filesystem::path(c.run.output) / data::run_layout::kSelection).string()));
  EXPECT_EQ(sel.at("epochs_done"), 3);
  EXPECT_EQ(sel.at("epochs"), 6);
  EXPECT_EQ(sel.at("patience"), 2);
  EXPECT_EQ(sel.at("chosen_epoch"), 1);
  c.train.epochs = 9;
  TrainOptions resume = quiet();
  resume.resume = true;
  const TrainReport again = run_training(c, registry, resume);
  EXPECT_TRUE(again.epochs.empty());
  EXPECT_EQ(again.epochs_done, 3);
  // Resumed without patience, the stopped run trains on.
  c.train.patience = 0;
  c.train.epochs = 4;
  const TrainReport on = run_training(c, registry, resume);
  EXPECT_EQ(on.epochs_done, 4);
  EXPECT_EQ(on.epochs.size(), 1u);
  // Patience with nothing to validate on is refused before training.
  ExperimentConfig blind = config("blind");
  blind.train.patience = 2;
  blind.data.subsets = {"T"};  // a train and the test sequence: no validation sequence
  try {
    run_training(blind, registry, quiet());
    ADD_FAILURE() << "patience without validation was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("train.patience: expected 0 when there is no validation"), std::string::npos)
        << e.what();
  }
}

// The selection record names the splits whose sequences the validation
// read, measured from the ids, not copied from data.val_split: pointed at
// the subset "T" (a train and the test sequence), the record says
// "T+train+test", and evaluating that checkpoint on test is refused.
TEST_F(Fixture, SelectionRecordNamesTheSplitsTheValidationRead) {
  ExperimentConfig c = config("leaky");
  c.train.epochs = 1;
  c.data.val_split = "T";
  run_training(c, registry, quiet());
  const CheckpointState best = load_checkpoint(checkpoint_path(c, "best"), *open_session(c, registry).model, nullptr);
  EXPECT_EQ(best.chosen_on, "T+train+test");
  EXPECT_TRUE(data::run_layout::chosen_on_names(best.chosen_on, "test"));
  EXPECT_FALSE(data::run_layout::chosen_on_names(best.chosen_on, "tes"));
  EvalOptions o;
  o.progress = false;
  try {
    run_evaluation(c, registry, o);
    ADD_FAILURE() << "a checkpoint chosen on a test sequence was evaluated on test";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("selection.chosen_on: expected a checkpoint chosen on a split other than "
                                         "data.test_split 'test', got one chosen on 'T+train+test'"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(Fixture, ResumingGivesTheSameModelAsOneRun) {
  ExperimentConfig straight = config("straight");
  straight.train.epochs = 3;
  run_training(straight, registry, quiet());

  ExperimentConfig split = config("split");
  split.train.epochs = 1;
  run_training(split, registry, quiet());
  split.train.epochs = 3;
  TrainOptions resume = quiet();
  resume.resume = true;
  const TrainReport r = run_training(split, registry, resume);
  EXPECT_EQ(r.epochs.size(), 2u);  // epochs 2 and 3 only
  EXPECT_EQ(r.epochs_done, 3);
  EXPECT_TRUE(at::equal(params_of(straight, registry), params_of(split, registry)));

  // The per-epoch history survives the resume: the same three epochs in
  // both checkpoints and in selection.json.
  const auto history = [&](const ExperimentConfig& c) {
    Session s = open_session(c, registry);
    return load_checkpoint(checkpoint_path(c, "last"), *s.model, nullptr);
  };
  const CheckpointState a = history(straight), b = history(split);
  ASSERT_EQ(a.val_mm_by_epoch.size(), 3u);
  ASSERT_EQ(a.loss_by_epoch.size(), 3u);
  EXPECT_EQ(a.val_mm_by_epoch, b.val_mm_by_epoch);
  EXPECT_EQ(a.loss_by_epoch, b.loss_by_epoch);
  ASSERT_EQ(b.windows_by_epoch.size(), 3u) << "the windows of the epochs before the resume are kept";
  EXPECT_EQ(a.windows_by_epoch, b.windows_by_epoch);
  for (double w : b.windows_by_epoch) EXPECT_GT(w, 0.0);
  for (double v : a.val_mm_by_epoch) EXPECT_GT(v, 0.0);
  std::ifstream file(split.run.output + "/selection.json");
  const nlohmann::json selection = nlohmann::json::parse(file);
  ASSERT_EQ(selection.at("val_error_mm_by_epoch").size(), 3u);
  EXPECT_DOUBLE_EQ(selection.at("val_error_mm_by_epoch")[2].get<double>(), b.val_mm_by_epoch[2]);
  EXPECT_DOUBLE_EQ(selection.at("best_val_error_mm").get<double>(),
                   *std::min_element(b.val_mm_by_epoch.begin(), b.val_mm_by_epoch.end()));
  EXPECT_EQ(selection.at("source_revision").get<std::string>(), source_revision());  // the code that trained it
}

TEST_F(Fixture, TrainingNoiseChangesTheStartStateAndStaysDeterministic) {
  auto train = [&](const std::string& run, double noise) {
    ExperimentConfig c = config(run);
    c.train.epochs = 1;
    c.train.noise_std = noise;
    return run_training(c, registry, quiet()).first_loss;
  };
  const double clean = train("clean", 0.0), noisy = train("noisy", 0.01), again = train("again", 0.01);
  // 1 cm of noise on the start positions (so on the start velocity too)
  // makes the first batch's loss larger than from the clean state...
  EXPECT_GT(noisy, clean);
  // ...and the same seed gives the same noise.
  EXPECT_DOUBLE_EQ(noisy, again);
  EXPECT_TRUE(at::equal(params_of(config("noisy"), registry), params_of(config("again"), registry)));
}

TEST_F(Fixture, CheckpointRestoresParametersAndNormalisation) {
  ExperimentConfig c = config("ckpt");
  Session a = open_session(c, registry);
  auto& tiny = dynamic_cast<testing::TinyModel&>(*a.model);
  {
    at::NoGradGuard g;
    tiny.gain_.fill_(0.75);
  }
  CheckpointState saved;
  saved.epochs_done = 2, saved.steps = 17, saved.best_val_mm = 3.5, saved.model_name = "tiny";
  save_checkpoint(dir.path() + "/x.pt", *a.model, nullptr, saved);
  Session b = open_session(c, registry);
  b.model->set_normalization(zoo::Normalization::identity());
  const CheckpointState st = load_checkpoint(dir.path() + "/x.pt", *b.model, nullptr);
  EXPECT_EQ(st.epochs_done, 2);
  EXPECT_EQ(st.steps, 17);
  EXPECT_DOUBLE_EQ(st.best_val_mm, 3.5);
  EXPECT_FLOAT_EQ(dynamic_cast<testing::TinyModel&>(*b.model).gain_.item<float>(), 0.75f);
  EXPECT_TRUE(at::equal(b.model->normalization().garment_velocity.std, a.model->normalization().garment_velocity.std));
  EXPECT_FALSE(at::equal(a.model->normalization().garment_position.std, at::ones({3})));

  // Another model's checkpoint, and a file that is not one.
  Session other = open_session(config("ckpt2", "exploding"), registry);
  CheckpointState theirs;
  theirs.epochs_done = 0, theirs.steps = 0, theirs.best_val_mm = -1, theirs.model_name = "exploding";
  save_checkpoint(dir.path() + "/other.pt", *other.model, nullptr, theirs);
  EXPECT_THROW(load_checkpoint(dir.path() + "/other.pt", *b.model, nullptr), InputError);
  std::ofstream(dir.path() + "/junk.pt") << "not a checkpoint";
  EXPECT_THROW(load_checkpoint(dir.path() + "/junk.pt", *b.model, nullptr), InputError);
  EXPECT_THROW(load_checkpoint(dir.path() + "/missing.pt", *b.model, nullptr), InputError);
}

// A checkpoint carries a checksum of its archive: 200 flipped bytes, a
// truncated file or a damaged header are refused on load with one line
// naming the file; so is a bare torch archive (no checksum header).
// "tiny" as another width would make it: `shift` of 5 values, not 3.
class WiderTiny : public zoo::Model {
 public:
  WiderTiny() : Model("tiny") {
    register_parameter("gain", at::scalar_tensor(0.5, at::kFloat));
    register_parameter("shift", at::zeros({5}, at::kFloat));
  }
  cfg::Node config() const override { return cfg::to_node(testing::TinyParams()); }

 protected:
  zoo::StepOutput predict(const zoo::StepInput& in) override {
    zoo::StepOutput out;
    for (const zoo::GarmentState& g : in.garments) out.garments.push_back(g.current);
    return out;
  }
};

TEST_F(Fixture, ResumingWithAnotherModelShapeIsOneLineAndStartsNothing) {
  ExperimentConfig c = config("shape");
  run_training(c, registry, quiet());
  zoo::Registry wider;
  wider.add("tiny", "test model",
            [](const cfg::Node&) -> std::shared_ptr<zoo::Model> { return std::make_shared<WiderTiny>(); });
  TrainOptions resume = quiet();
  resume.resume = true;
  bool started = false;
  resume.started = [&] { started = true; };
  try {
    run_training(c, wider, resume);
    ADD_FAILURE() << "a checkpoint of another shape resumed";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), checkpoint_path(c, "last") +
                                         ": model parameter shift: expected shape [5] (the model 'tiny' as "
                                         "configured), got [3] in the checkpoint (trained with other model.params)");
  }
  EXPECT_FALSE(started);  // what the caller writes at the start (experiment.yaml) stays as it was
}

TEST_F(Fixture, DamagedCheckpointIsRefusedWithOneLine) {
  ExperimentConfig c = config("ckpt3");
  Session a = open_session(c, registry);
  const std::string good = dir.path() + "/good.pt";
  CheckpointState state;
  state.epochs_done = 1, state.steps = 2, state.best_val_mm = 3.0, state.model_name = "tiny";
  save_checkpoint(good, *a.model, nullptr, state);
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.rfind("layers-checkpoint 1 fnv1a64 ", 0), 0u);
  EXPECT_EQ(load_checkpoint(good, *a.model, nullptr).checksum, bytes.substr(28, 16));  // the header's hash
  auto write = [&](const std::string& name, const std::string& content) {
    std::ofstream(dir.path() + "/" + name, std::ios::binary) << content;
    return dir.path() + "/" + name;
  };
  auto message = [&](const std::string& file) {
    try {
      load_checkpoint(file, *a.model, nullptr);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  std::string flipped = bytes;
  for (std::size_t i = 0; i < 200; ++i) flipped[bytes.size() / 2 + i] ^= 0x5a;
  const std::string f = write("flipped.pt", flipped);
  EXPECT_EQ(message(f).rfind(f + ": checksum: expected fnv1a64 ", 0), 0u) << message(f);
  EXPECT_NE(message(f).find("(the file is damaged)"), std::string::npos);
  EXPECT_EQ(message(f).find('\n'), std::string::npos) << message(f);
  const std::string t = write("truncated.pt", bytes.substr(0, bytes.size() - 100));
  EXPECT_NE(message(t).find("(truncated or damaged)"), std::string::npos) << message(t);
  const std::string h = write("header.pt", "layers-checkpoint 1 fnv1a64 zz\n" + bytes.substr(bytes.find('\n') + 1));
  EXPECT_NE(message(h).find("expected 'layers-checkpoint 1 fnv1a64 <16 hex digits> <size>'"), std::string::npos)
      << message(h);
  // The archive alone, as written before checksums, whole or with a
  // flipped byte: refused, since damage to it could not be detected.
  const std::string bare = bytes.substr(bytes.find('\n') + 1);
  std::string bare_flipped = bare;
  bare_flipped[bare.size() / 2] ^= 0x01;
  for (const std::string& content : {bare, bare_flipped}) {
    const std::string legacy = write("legacy.pt", content);
    EXPECT_NE(message(legacy).find("got a bare torch archive without a checksum"), std::string::npos)
        << message(legacy);
    EXPECT_EQ(message(legacy).find('\n'), std::string::npos) << message(legacy);
  }
  // A folder, a device that never ends, a header of raw bytes: one line
  // each, before any read (no bytes echoed as they are).
  EXPECT_EQ(message(dir.path()), dir.path() +
                                     ": checkpoint: expected a checkpoint file (checkpoint-best.pt or "
                                     "checkpoint-last.pt), got a folder");
  EXPECT_NE(message("/dev/zero").find("expected a regular file"), std::string::npos) << message("/dev/zero");
  const std::string raw = write("raw.pt", std::string("layers-checkpoint 1 fnv1a64 \xff\x01 7\n") + "payload");
  EXPECT_NE(message(raw).find("\\xff\\x01"), std::string::npos) << message(raw);
}

TEST_F(Fixture, DivergenceIsRecordedNotThrown) {
  ExperimentConfig c = config("boom", "exploding");
  Session s = open_session(c, registry);
  const SequenceRollout r = rollout_sequence(s, "s4", 0, 1000.0, true);
  ASSERT_EQ(r.result.frames.size(), 10u);  // 12 frames: 0 and 1 given
  ASSERT_GE(r.result.diverged_at, 2);
  EXPECT_FALSE(r.result.diverge_reason.empty());
  EXPECT_DOUBLE_EQ(value_of(r.result.frames.back(), "error_mm").scene, 1000.0);
  EXPECT_TRUE(r.result.frames.back().diverged);
  ASSERT_EQ(r.result.predictions.size(), 2u);
  EXPECT_TRUE(at::isfinite(r.result.predictions[0]).all().item<bool>());
}

TEST_F(Fixture, EvaluationWritesMetricsAndPredictions) {
  const EvalReport r = trained_and_evaluated("eval");
  EXPECT_EQ(r.split, "test");
  EXPECT_EQ(r.sequences, 1);
  EXPECT_EQ(r.frames, 6);
  EXPECT_EQ(r.per_type.size(), 2u);  // tshirt and jacket
  EXPECT_GT(r.overall.at("error_mm").mean, 0.0);
  std::ifstream in(r.out_dir + "/metrics.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["model"], "tiny");
  // The results name the checkpoint bytes they came from.
  std::ifstream ckpt(j["checkpoint"].get<std::string>(), std::ios::binary);
  std::string header;
  std::getline(ckpt, header);
  EXPECT_EQ(header.substr(28, 16), j["checkpoint_fnv1a64"].get<std::string>());
  EXPECT_EQ(j["by_step"].size(), 6u);
  EXPECT_NEAR(j["overall"]["error_mm"]["mean"].get<double>(), r.overall.at("error_mm").mean, 1e-9);
  const data::Dataset pred = data::Dataset::open(r.out_dir + "/predictions.h5");
  ASSERT_TRUE(pred.contains("s4"));
  EXPECT_EQ(pred.info("s4").n_frames, 8);  // 2 given + 6 predicted
  EXPECT_TRUE(std::filesystem::exists(r.out_dir + "/sequences.csv"));
}

// Exact crossings beside the vertex-normal rates: a prediction that pushes
// garment faces through the body, one that pushes the outer layer through
// the inner one; the ground truth crosses nothing.
TEST_F(Fixture, RolloutMeasuresPlantedCrossings) {
  // The planted models are far from the truth: no divergence bound.
  const auto roll = [&](const std::string& model, std::int64_t horizon = 3, double bound = 1e6) {
    ExperimentConfig c = config(model, model);
    Session s = open_session(c, registry);
    return rollout_sequence(s, "s4", horizon, bound, false).result;
  };
  const RolloutResult body = roll("through_body");
  ASSERT_EQ(body.frames.size(), 3u);
  for (const FrameMetrics& m : body.frames) {
    EXPECT_GT(value_of(m, "h_crossing").scene, 0.05) << "frame " << m.frame;
    EXPECT_LT(value_of(m, "h_crossing").scene, 1.0);
    EXPECT_DOUBLE_EQ(value_of(m, "l_crossing").scene, 0.0) << "both layers moved together";
    ASSERT_EQ(value_of(m, "h_crossing").garments.size(), 2u);
    EXPECT_GT(value_of(m, "h_crossing").garments[0], 0.0);
    EXPECT_GT(value_of(m, "h_crossing").garments[1], 0.0);
    EXPECT_DOUBLE_EQ(truth_of(m, "h_crossing"), 0.0);
    EXPECT_DOUBLE_EQ(truth_of(m, "l_crossing"), 0.0);
    EXPECT_TRUE(std::isfinite(value_of(m, "h_collision").scene));
  }
  const RolloutResult inner = roll("through_inner");
  for (const FrameMetrics& m : inner.frames) {
    EXPECT_GT(value_of(m, "l_crossing").scene, 0.05) << "frame " << m.frame;
    // Both L-collisions are measured; ours leaves out what the paper's counts beside an open edge.
    EXPECT_TRUE(std::isfinite(value_of(m, "l_collision_plain").scene)) << "frame " << m.frame;
    EXPECT_GE(value_of(m, "l_collision_plain").scene, value_of(m, "l_collision").scene) << "frame " << m.frame;
    EXPECT_GE(truth_of(m, "l_collision_plain"), truth_of(m, "l_collision")) << "frame " << m.frame;
    EXPECT_DOUBLE_EQ(value_of(m, "h_crossing").scene, 0.0) << "both layers stay clear of the body";
    EXPECT_DOUBLE_EQ(truth_of(m, "l_crossing"), 0.0);
  }
  // Without rates (training's validation): the same errors, every rate NaN.
  {
    ExperimentConfig c = config("norates", "through_body");
    Session s = open_session(c, registry);
    const RolloutResult plain = rollout_sequence(s, "s4", 3, 1e6, false, /*rates=*/false).result;
    ASSERT_EQ(plain.frames.size(), 3u);
    EXPECT_DOUBLE_EQ(value_of(plain.frames[0], "error_mm").scene, value_of(body.frames[0], "error_mm").scene);
    EXPECT_TRUE(std::isnan(value_of(plain.frames[0], "h_crossing").scene));
    EXPECT_TRUE(std::isnan(value_of(plain.frames[0], "h_collision").scene));
    EXPECT_TRUE(std::isnan(truth_of(plain.frames[0], "l_crossing")));
  }
  // After divergence no crossing rate, like the collision rates.
  const RolloutResult boom = roll("exploding", 0, 1000.0);
  ASSERT_TRUE(boom.frames.back().diverged);
  EXPECT_TRUE(std::isnan(value_of(boom.frames.back(), "h_crossing").scene));
  EXPECT_TRUE(std::isnan(value_of(boom.frames.back(), "l_crossing").scene));
  EXPECT_TRUE(std::isnan(value_of(boom.frames.back(), "l_collision_plain").scene));
}

// A metric added to the registry reaches every output without touching the
// evaluator or the report: metrics.json (overall, per type, per sequence
// and garment, by step), sequences.csv, and the report's tables.
TEST_F(Fixture, ARegisteredMetricReachesMetricsJsonAndTheReport) {
  metrics::MetricDef speed;
  speed.key = "test_garment_speed_mm";
  speed.label = "garment speed (mm/frame)";
  speed.description = "mean distance a garment vertex moves from the previous frame";
  speed.rule = "none (a test metric)";
  speed.unit = metrics::Unit::Millimetre;
  speed.compute = [](const metrics::FrameScene& s) {
    return metrics::vertex_weighted(
        s, [&](std::size_t g) { return metrics::euclidean_error_mm(s.garment(g).vertices, s.previous(g)); });
  };
  const metrics::ScopedMetric added(speed);
  const EvalReport r = trained_and_evaluated("speed");
  const std::string run_folder = dir.path() + "/speed";
  ASSERT_EQ(r.overall.count("test_garment_speed_mm"), 1u);
  EXPECT_GT(r.overall.at("test_garment_speed_mm").mean, 0.0) << "the garments move in the fixture";
  std::ifstream in(r.out_dir + "/metrics.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_NEAR(j["overall"]["test_garment_speed_mm"]["mean"].get<double>(), r.overall.at("test_garment_speed_mm").mean,
              1e-12);
  EXPECT_EQ(j["per_type"]["jacket"]["test_garment_speed_mm"]["count"], 1);
  EXPECT_TRUE(j["per_sequence"][0]["test_garment_speed_mm"].is_number());
  EXPECT_TRUE(j["per_sequence"][0]["garments"][0]["test_garment_speed_mm"].is_number());
  EXPECT_TRUE(j["by_step"][0]["test_garment_speed_mm"].is_number());
  EXPECT_FALSE(j["truth"].contains("test_garment_speed_mm")) << "not measured on the ground truth";
  std::ifstream csv(r.out_dir + "/sequences.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find(",test_garment_speed_mm"), std::string::npos) << header;

  const report::RunResults run = report::load_run(run_folder);
  ASSERT_TRUE(run.eval.has_value());
  EXPECT_NEAR(run.eval->overall.get("test_garment_speed_mm").mean, r.overall.at("test_garment_speed_mm").mean, 1e-12);
  report::ReportInputs inputs;
  inputs.charts = false;
  const report::ReportResult made = report::write_report({run}, inputs, dir.path() + "/report");
  const std::string md = read_text_file(made.report);
  EXPECT_NE(md.find("| garment speed (mm/frame) |"), std::string::npos) << "a column of the models table";
  EXPECT_NE(md.find("mean distance a garment vertex moves"), std::string::npos) << "its description";
  const std::string summary = read_text_file(dir.path() + "/report/summary.csv");
  EXPECT_NE(summary.find(",test_garment_speed_mm,test_garment_speed_mm_std,"), std::string::npos);
}

TEST_F(Fixture, EvaluationReportsPlantedCrossings) {
  ExperimentConfig c = config("planted", "through_inner");
  c.eval.diverge_mm = 1e6;
  {
    Session s = open_session(c, registry);
    std::filesystem::create_directories(std::filesystem::path(checkpoint_path(c, "best")).parent_path());
    CheckpointState state;
    state.model_name = s.model->name();
    save_checkpoint(checkpoint_path(c, "best"), *s.model, nullptr, state);
  }
  EvalOptions o;
  o.progress = false;
  const EvalReport r = run_evaluation(c, registry, o);
  EXPECT_GT(r.overall.at("l_crossing").mean, 0.05);
  EXPECT_EQ(r.overall.at("l_crossing").count, 1);
  EXPECT_DOUBLE_EQ(r.overall.at("h_crossing").mean, 0.0);
  EXPECT_DOUBLE_EQ(r.truth.at("h_crossing").mean, 0.0);
  EXPECT_DOUBLE_EQ(r.truth.at("l_crossing").mean, 0.0);
  std::ifstream in(r.out_dir + "/metrics.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_NEAR(j["overall"]["l_crossing"]["mean"].get<double>(), r.overall.at("l_crossing").mean, 1e-12);
  EXPECT_EQ(j["overall"]["h_crossing"]["count"], 1);
  EXPECT_EQ(j["truth"]["l_crossing"], 0.0);
  EXPECT_TRUE(j["per_type"]["jacket"]["l_crossing"]["mean"].get<double>() > 0.05);
  EXPECT_EQ(j["per_type"]["tshirt"]["l_crossing"]["count"], 0) << "L belongs to the outer garment";
  EXPECT_TRUE(j["by_step"][0]["l_crossing"].get<double>() > 0.05);
  const nlohmann::json& seq = j["per_sequence"][0];
  EXPECT_NEAR(seq["l_crossing"].get<double>(), r.overall.at("l_crossing").mean, 1e-12);
  EXPECT_EQ(seq["truth_l_crossing"], 0.0);
  EXPECT_TRUE(seq["garments"][1].contains("h_crossing"));
  // The paper's L-collision (plain nearest vertex) beside ours everywhere
  // ours is; the open-edge rule only leaves vertices out.
  EXPECT_EQ(r.overall.at("l_collision_plain").count, 1);
  EXPECT_GE(r.overall.at("l_collision_plain").mean, r.overall.at("l_collision").mean);
  EXPECT_GE(r.truth.at("l_collision_plain").mean, r.truth.at("l_collision").mean);
  EXPECT_NEAR(j["overall"]["l_collision_plain"]["mean"].get<double>(), r.overall.at("l_collision_plain").mean, 1e-12);
  EXPECT_NEAR(j["truth"]["l_collision_plain"].get<double>(), r.truth.at("l_collision_plain").mean, 1e-12);
  EXPECT_EQ(j["per_type"]["jacket"]["l_collision_plain"]["count"], 1);
  EXPECT_EQ(j["per_type"]["tshirt"]["l_collision_plain"]["count"], 0) << "L belongs to the outer garment";
  EXPECT_TRUE(j["by_step"][0]["l_collision_plain"].is_number());
  EXPECT_NEAR(seq["l_collision_plain"].get<double>(), r.overall.at("l_collision_plain").mean, 1e-12);
  EXPECT_TRUE(seq["truth_l_collision_plain"].is_number());
  EXPECT_TRUE(seq["garments"][1]["l_collision_plain"].is_number());
  EXPECT_TRUE(seq["garments"][0]["l_collision_plain"].is_null());
  std::ifstream csv(r.out_dir + "/sequences.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("sequence,motion,tags,garment,type,layer,diverged_at,error_mm,h_collision,l_collision,"
                         "l_collision_plain,h_crossing,l_crossing",
                         0),
            0u)
      << "the registered metrics, in registry order: " << header;
}

TEST_F(Fixture, MissingDatasetIsAClearError) {
  ExperimentConfig c = config("nodata");
  c.data.dataset.clear();
  try {
    open_session(c, registry);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("data.dataset"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace layers::train
