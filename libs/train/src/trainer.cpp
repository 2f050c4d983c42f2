// The training loop (see trainer.h).
#include "layers/train/trainer.h"

#include <ATen/Context.h>
#include <spdlog/spdlog.h>
#include <torch/nn/utils/clip_grad.h>
#include <torch/optim/adam.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <optional>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/core/memory.h"
#include "layers/core/progress.h"
#include "layers/core/source_revision.h"
#include "layers/data/run_layout.h"
#include "layers/dist/group.h"
#include "layers/dist/tensors.h"
#include "layers/metrics/measures.h"
#include "layers/train/checkpoint.h"
#include "layers/train/frame_loss.h"
#include "layers/train/session.h"
#include "layers/train/window_loader.h"

namespace layers::train {
namespace {

std::vector<at::Tensor> trainable(zoo::Model& model) {
  std::vector<at::Tensor> out;
  for (const at::Tensor& p : model.parameters(true))
    if (p.requires_grad()) out.push_back(p);
  return out;
}

double learning_rate(const TrainConfig& t, int epoch) { return t.lr * std::pow(t.lr_decay, epoch / t.lr_decay_every); }

void set_learning_rate(torch::optim::Adam& optimizer, double lr) {
  for (auto& group : optimizer.param_groups()) static_cast<torch::optim::AdamOptions&>(group.options()).lr(lr);
}

// One window: curriculum steps without gradient, then the loss steps.
// Returns the loss (already backpropagated, divided by `scale`).
double train_window(Session& s, const Sample& sample, std::int64_t free_steps, std::int64_t loss_steps,
                    const zoo::TrainingContext& context, double scale, double noise_std) {
  zoo::Model& model = *s.model;
  model.prepare(*sample.statics);
  const zoo::SequenceStatic& seq = model.sequence();
  const FrameTensors frames = to_device(sample.frames, s.device);
  std::int64_t i = 1;  // history = 1: row 1 is the window's start frame
  std::vector<zoo::GarmentState> states = true_states(frames, i);
  // Training noise: the window starts from perturbed current positions
  // (so a perturbed velocity too) and the loss still asks for the true
  // next frames, so the model learns to pull a drifting state back.
  if (noise_std > 0)
    for (zoo::GarmentState& g : states) g.current = g.current + at::randn_like(g.current) * noise_std;
  {
    torch::NoGradGuard no_grad;
    for (std::int64_t r = 0; r < free_steps; ++r, ++i) {
      zoo::StepOutput out = model.step(step_input(frames, i, states));
      for (std::size_t k = 0; k < states.size(); ++k) states[k] = {states[k].current, out.garments[k].detach()};
    }
  }
  at::Tensor total;
  for (std::int64_t r = 0; r < loss_steps; ++r, ++i) {
    zoo::StepOutput out = model.step(step_input(frames, i, states));
    std::vector<at::Tensor> truth;
    for (const at::Tensor& g : frames.garments) truth.push_back(g[i + 1]);
    LossSum loss = frame_loss(seq, out.garments, truth, frames.body[i + 1], s.config.loss);
    total = total.defined() ? total + loss.total : loss.total;
    for (std::size_t k = 0; k < states.size(); ++k) states[k] = {states[k].current, out.garments[k]};
  }
  for (const zoo::LossTerm& term : model.auxiliary_losses(context)) total = total + term.value;
  total = total / static_cast<double>(loss_steps) / scale;
  const double value = total.item<double>() * scale;
  if (!std::isfinite(value))
    throw Error("training diverged: loss " + std::to_string(value) + " on sequence '" + sample.id + "' frame " +
                std::to_string(sample.start) + " (lower train.lr or check the data)");
  total.backward();
  return value;
}

// The validation of one epoch: the mean rollout error (mm; -1 without
// validation sequences) and the ids of the sequences it read.
struct Validation {
  double mm = -1;
  std::vector<std::string> read;
};

// Mean rollout error (mm) over the validation sequences (no collision or
// crossing rates: they cost as much as the rollout and are not used here);
// with ranks, each rolls out every size-th sequence and the sums are added.
Validation validate(Session& s, dist::Group* group) {
  const TrainConfig& t = s.config.train;
  std::vector<std::string> ids = select_sequences(s.dataset, s.config.data.val_split, s.config.data.subsets);
  if (t.val_sequences > 0 && ids.size() > static_cast<std::size_t>(t.val_sequences)) ids.resize(t.val_sequences);
  const std::size_t rank = group ? static_cast<std::size_t>(group->rank()) : 0;
  const std::size_t ranks = group ? static_cast<std::size_t>(group->size()) : 1;
  std::vector<double> sum_count{0, 0};
  for (std::size_t k = rank; k < ids.size(); k += ranks) {
    const SequenceRollout r = rollout_sequence(s, ids[k], t.val_horizon, s.config.eval.diverge_mm,
                                               /*keep_predictions=*/false, /*rates=*/false);
    std::vector<double> per_frame;
    for (const FrameMetrics& m : r.result.frames) per_frame.push_back(m.error_mm());
    sum_count[0] += metrics::sequence_mean(per_frame);
    sum_count[1] += 1;
  }
  if (group) group->allreduce_sum(sum_count);
  Validation v;
  v.read = ids;
  if (sum_count[1] > 0) v.mm = sum_count[0] / sum_count[1];
  return v;
}

// The splits (of data's train, val and test splits) holding the sequences
// a validation read, joined by '+' ("val" when all of them are val's
// only); a sequence in none of them adds "unlisted". What the selection
// record says chose the checkpoint: measured from the ids read, not copied
// from the config.
std::string splits_read(const data::Dataset& dataset, const DataConfig& d, const std::vector<std::string>& read) {
  std::vector<std::string> names;
  for (const std::string& n : {d.val_split, d.train_split, d.test_split})
    if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
  std::string out;
  std::vector<bool> listed(read.size(), false);
  for (const std::string& n : names) {
    if (!dataset.splits().has(n)) continue;
    const std::vector<std::string>& ids = dataset.splits().get(n);
    bool holds = false;
    for (std::size_t k = 0; k < read.size(); ++k)
      if (std::find(ids.begin(), ids.end(), read[k]) != ids.end()) holds = listed[k] = true;
    if (holds) out += (out.empty() ? "" : "+") + n;
  }
  if (std::find(listed.begin(), listed.end(), false) != listed.end())
    out += (out.empty() ? "" : "+") + std::string("unlisted");
  return out;
}

// All ranks must continue from the same checkpoint: they read it from a
// run.output they share.
void check_same_start(dist::Group& group, const CheckpointState& state, const std::string& checkpoint) {
  const double e = state.epochs_done, st = static_cast<double>(state.steps);
  std::vector<double> sums{e, e * e, st, st * st};
  group.allreduce_sum(sums);
  const double n = group.size();
  // All equal exactly when the sum of squares times n is the squared sum.
  if (sums[1] * n != sums[0] * sums[0] || sums[3] * n != sums[2] * sums[2])
    throw InputError(checkpoint, "epochs_done",
                     "the same checkpoint on every rank (run.output on a file system all ranks share)",
                     "epoch " + std::to_string(state.epochs_done) + " on rank " + std::to_string(group.rank()) +
                         ", a different one on another rank");
}

// What compares epochs for the best checkpoint (the selection record).
std::string selection_metric(const TrainConfig& t) {
  return "mean rollout error (mm), " + std::to_string(t.val_horizon) + " frames, " +
         (t.val_sequences > 0 ? "first " + std::to_string(t.val_sequences) : std::string("all")) + " sequences";
}

// <run.output>/selection.json: what chose checkpoint-best.pt, for people
// (the evaluator reads the same record from the checkpoint itself).
void write_selection(const ExperimentConfig& config, const CheckpointState& state) {
  const bool chosen = !state.chosen_on.empty();
  const nlohmann::ordered_json doc = {
      {"checkpoint", data::run_layout::checkpoint("best")},
      {"chosen_on", chosen ? nlohmann::ordered_json(state.chosen_on) : nlohmann::ordered_json("none")},
      {"metric", chosen ? nlohmann::ordered_json(state.metric) : nlohmann::ordered_json(nullptr)},
      {"chosen_epoch", chosen ? nlohmann::ordered_json(state.chosen_epoch) : nlohmann::ordered_json(nullptr)},
      {"best_val_error_mm", chosen ? nlohmann::ordered_json(state.best_val_mm) : nlohmann::ordered_json(nullptr)},
      {"epochs_done", state.epochs_done},
      {"epochs", state.epochs},
      {"loss_by_epoch", state.loss_by_epoch},
      {"val_error_mm_by_epoch", state.val_mm_by_epoch},
      {"windows_by_epoch", state.windows_by_epoch},
      // The validation's protocol in fields (the metric above in words):
      // rollout frames and sequences (0: every one of the split).
      {"val_split", config.data.val_split},
      {"val_horizon", config.train.val_horizon},
      {"val_sequences", config.train.val_sequences},
      {"patience", config.train.patience},
      {"train_split", config.data.train_split},
      {"test_split", config.data.test_split},
      {"source_revision", source_revision()}};  // the build that wrote this record
  write_text_atomic((std::filesystem::path(config.run.output) / data::run_layout::kSelection).string(),
                    doc.dump(2) + "\n");
}

}  // namespace

std::string checkpoint_path(const ExperimentConfig& config, const std::string& which) {
  return (std::filesystem::path(config.run.output) / data::run_layout::checkpoint(which)).string();
}

namespace {

// One training run: what its phases share. The run folder is made, and
// options.started called, just before the first checkpoint is saved: a
// sequence refused by the integrity check on its first read
// (data::Dataset) ends the run with nothing written.
struct TrainingRun {
  const ExperimentConfig& config;
  const TrainOptions& options;
  dist::Group* group;
  bool root;
  Session s;
  TrainReport report;
  CheckpointState state;
  bool claimed = false;
  bool first_batch = true;      // of this process (a resumed run's first too)
  std::string validation_read;  // the splits the latest validation read (splits_read)

  // Saves checkpoint-<which>.pt with the selection record naming it.
  void save(const char* which, const torch::optim::Optimizer* optimizer) {
    if (!claimed) {
      std::filesystem::create_directories(config.run.output);
      if (options.started) options.started();
      claimed = true;
    }
    state.kind = which;
    save_checkpoint(checkpoint_path(config, which), *s.model, optimizer, state);
  }
};

TrainingRun open_run(const ExperimentConfig& config, const zoo::Registry& registry, const TrainOptions& options) {
  dist::Group* group = options.group;
  TrainingRun run{config,
                  options,
                  group,
                  !group || group->is_root(),
                  open_session(config, registry, group ? group->local_rank() : -1),
                  {},
                  {},
                  false,
                  true,
                  {}};
  run.report.run_dir = config.run.output;
  run.report.last_checkpoint = checkpoint_path(config, "last");
  run.report.best_checkpoint = checkpoint_path(config, "best");
  run.state.model_name = run.s.model->name();
  run.state.epochs = config.train.epochs;
  return run;
}

// A resumed run's checkpoint, and on several ranks the same start
// everywhere (rank 0's parameters and buffers).
void resume_and_sync(TrainingRun& run, torch::optim::Adam& optimizer) {
  if (run.options.resume && std::filesystem::exists(run.report.last_checkpoint)) {
    run.state = load_checkpoint(run.report.last_checkpoint, *run.s.model, &optimizer);
    run.state.epochs = run.config.train.epochs;
    spdlog::info("resuming from {} after epoch {} ({} steps)", run.report.last_checkpoint, run.state.epochs_done,
                 run.state.steps);
  }
  if (!run.group) return;
  dist::Group& group = *run.group;
  check_same_start(group, run.state, run.report.last_checkpoint);
  std::vector<at::Tensor> tensors = run.s.model->parameters(true);
  for (const at::Tensor& b : run.s.model->buffers(true)) tensors.push_back(b);
  dist::broadcast_from_root(group, tensors);
  spdlog::info("data-parallel training: {} ranks ({}), batch {} per rank", group.size(), group.backend(),
               run.config.train.batch_size);
}

LoaderOptions loader_options(const TrainingRun& run) {
  const TrainConfig& t = run.config.train;
  LoaderOptions lo;
  lo.split = run.config.data.train_split;
  lo.subsets = run.config.data.subsets;
  lo.selection = run.s.selection;
  lo.batch_size = t.batch_size;
  lo.windows_per_epoch = t.windows_per_epoch;
  lo.stride = t.window_stride;
  lo.prefetch = t.prefetch;
  lo.seed = run.config.run.seed;
  if (run.group) lo.rank = run.group->rank(), lo.world = run.group->size();
  return lo;
}

// One epoch of optimiser steps over the loader's batches (the mean
// gradient over the ranks); the summary without its validation error.
EpochSummary train_epoch(TrainingRun& run, WindowLoader& loader, torch::optim::Adam& optimizer,
                         const std::vector<at::Tensor>& params, int epoch) {
  const TrainConfig& t = run.config.train;
  dist::Group* group = run.group;
  const std::int64_t loss_steps = t.two_step ? 2 : 1;
  // Resume-independent; each rank draws its own training noise.
  at::manual_seed(run.config.run.seed * 7919 + static_cast<std::uint64_t>(epoch) +
                  (group ? 104729ULL * static_cast<std::uint64_t>(group->rank()) : 0));
  const double lr = learning_rate(t, epoch);
  set_learning_rate(optimizer, lr);
  const std::int64_t free_steps = std::min(epoch, t.curriculum_max);
  const std::size_t batches = loader.start_epoch(epoch, free_steps + loss_steps);
  run.s.model->train(true);
  Timer timer;
  const double comm_before = group ? group->comm_seconds() : 0;
  std::optional<Progress> progress;
  if (run.root)
    progress.emplace("epoch " + std::to_string(epoch + 1) + "/" + std::to_string(t.epochs), batches, "batches");
  double loss_sum = 0;
  std::int64_t frames = 0, windows = 0;
  std::size_t seen = 0;
  double data_seconds = 0, optimizer_seconds = 0;
  for (;;) {
    Timer wait;
    std::optional<Batch> batch = loader.next();
    data_seconds += wait.seconds();
    if (!batch) break;
    optimizer.zero_grad();
    const zoo::TrainingContext context{epoch, run.state.steps};
    double batch_loss = 0;
    for (const Sample& sample : *batch)
      batch_loss +=
          train_window(run.s, sample, free_steps, loss_steps, context, static_cast<double>(batch->size()), t.noise_std);
    batch_loss /= static_cast<double>(batch->size());
    std::int64_t batch_frames = static_cast<std::int64_t>(batch->size()) * loss_steps;
    windows += static_cast<std::int64_t>(batch->size()) * (group ? group->size() : 1);
    if (group) {
      // Mean gradient and loss over the ranks (every rank's batch is as
      // large), so the step is the one of the whole batch in one process.
      std::vector<double> sums{batch_loss, static_cast<double>(batch_frames)};
      dist::average_gradients(*group, params, sums);
      batch_loss = sums[0] / group->size();
      batch_frames = static_cast<std::int64_t>(sums[1]);
    }
    Timer step;
    if (t.grad_clip > 0) torch::nn::utils::clip_grad_norm_(params, t.grad_clip);
    optimizer.step();
    optimizer_seconds += step.seconds();
    ++run.state.steps;
    ++seen;
    if (run.first_batch) run.report.first_loss = batch_loss;
    run.first_batch = false;
    loss_sum += batch_loss;
    frames += batch_frames;
    char extra[96];
    std::snprintf(extra, sizeof extra, "loss %.4g  %.1f frames/s", loss_sum / static_cast<double>(seen),
                  static_cast<double>(frames) / std::max(timer.seconds(), 1e-9));
    if (progress) progress->advance(1, extra);
  }
  if (progress) progress->finish();
  EpochSummary e;
  e.epoch = epoch + 1;
  e.loss = seen ? loss_sum / static_cast<double>(seen) : 0;
  e.seconds = timer.seconds();
  e.frames_per_second = static_cast<double>(frames) / std::max(e.seconds, 1e-9);
  e.lr = lr;
  e.comm_seconds = group ? group->comm_seconds() - comm_before : 0;
  e.ranks = group ? group->size() : 1;
  e.data_seconds = data_seconds;
  e.optimizer_seconds = optimizer_seconds;
  e.peak_resident_mib = static_cast<double>(peak_resident_bytes()) / (1024.0 * 1024.0);
  e.windows = windows;
  return e;
}

// The epoch's history, and on rank 0 its checkpoints: last always, best
// when the validation error is the lowest so far (chosen on the validation
// split alone; check_selection keeps it off the test split).
void keep_epoch(TrainingRun& run, const EpochSummary& e, torch::optim::Adam& optimizer) {
  CheckpointState& state = run.state;
  const int epoch = e.epoch - 1;
  state.epochs_done = e.epoch;
  // A checkpoint from before the history was kept: the earlier epochs are unknown (NaN).
  state.loss_by_epoch.resize(static_cast<std::size_t>(epoch), std::nan(""));
  state.val_mm_by_epoch.resize(static_cast<std::size_t>(epoch), std::nan(""));
  state.loss_by_epoch.push_back(e.loss);
  state.windows_by_epoch.resize(static_cast<std::size_t>(epoch), std::nan(""));
  state.windows_by_epoch.push_back(static_cast<double>(e.windows));
  state.val_mm_by_epoch.push_back(e.val_error_mm);
  run.report.epochs.push_back(e);
  if (!run.root) {
    // The best-so-far bookkeeping as on rank 0 (it decides what is saved,
    // and train.patience when to stop).
    if (e.val_error_mm >= 0 && (state.best_val_mm < 0 || e.val_error_mm < state.best_val_mm)) {
      state.best_val_mm = e.val_error_mm;
      state.chosen_epoch = e.epoch;
    }
    return;
  }
  run.save("last", &optimizer);
  if (e.val_error_mm >= 0 && (state.best_val_mm < 0 || e.val_error_mm < state.best_val_mm)) {
    state.best_val_mm = e.val_error_mm;
    state.chosen_on = run.validation_read;
    state.metric = selection_metric(run.config.train);
    state.chosen_epoch = e.epoch;
    run.save("best", &optimizer);
    run.save("last", &optimizer);  // same best in both
  } else if (e.val_error_mm < 0) {
    run.save("best", &optimizer);  // no validation: the latest epoch, nothing chosen
  }
  write_selection(run.config, state);
  const int epochs = run.config.train.epochs;
  if (run.group)
    spdlog::info(
        "epoch {}/{}: loss {:.4g}, val error {:.2f} mm, lr {:.3g}, {:.1f} frames/s on {} ranks, {:.1f} s "
        "({:.1f}% in gradient exchange)",
        e.epoch, epochs, e.loss, e.val_error_mm, e.lr, e.frames_per_second, e.ranks, e.seconds,
        100.0 * e.comm_seconds / std::max(e.seconds, 1e-9));
  else
    spdlog::info(
        "epoch {}/{}: loss {:.4g}, val error {:.2f} mm, lr {:.3g}, {:.1f} frames/s, {:.1f} s ({:.1f}% waiting for "
        "data, {:.1f}% in the optimiser), peak memory {:.0f} MiB",
        e.epoch, epochs, e.loss, e.val_error_mm, e.lr, e.frames_per_second, e.seconds,
        100.0 * e.data_seconds / std::max(e.seconds, 1e-9), 100.0 * e.optimizer_seconds / std::max(e.seconds, 1e-9),
        e.peak_resident_mib);
}

// Epochs since the lowest validation error when train.patience of them
// have passed without a lower one (0: train on). The best epoch is the
// one checkpoint-best.pt holds (CheckpointState::chosen_epoch, kept on
// every rank and saved in the checkpoint, also by runs from before the
// per-epoch history), so the ranks stop together and a resumed run stops
// where one process would have.
int epochs_without_gain(const TrainConfig& t, const CheckpointState& state) {
  if (t.patience <= 0 || state.chosen_epoch <= 0) return 0;
  const int since = state.epochs_done - state.chosen_epoch;
  return since >= t.patience ? since : 0;
}

}  // namespace

TrainReport run_training(const ExperimentConfig& config, const zoo::Registry& registry, const TrainOptions& options) {
  TrainingRun run = open_run(config, registry, options);
  const std::vector<at::Tensor> params = trainable(*run.s.model);
  for (const at::Tensor& p : params) run.report.trainable_parameters += p.numel();
  if (params.empty()) {
    // Nothing to learn (reference models): the checkpoint holds the
    // normalisation, so evaluation runs the same way for every model.
    if (!run.root) return run.report;
    run.save("last", nullptr);
    run.save("best", nullptr);
    write_selection(config, run.state);
    spdlog::info("model '{}' has no trainable parameters: saved {} without training", run.s.model->name(),
                 run.report.last_checkpoint);
    return run.report;
  }
  torch::optim::Adam optimizer(params, torch::optim::AdamOptions(config.train.lr));
  resume_and_sync(run, optimizer);
  if (config.train.patience > 0 && select_sequences(run.s.dataset, config.data.val_split, config.data.subsets).empty())
    throw InputError(config.source, "train.patience",
                     "0 when there is no validation to stop on (the validation split '" + config.data.val_split +
                         "' has no sequences here)",
                     std::to_string(config.train.patience));
  WindowLoader loader(run.s.dataset, loader_options(run));
  for (int epoch = run.state.epochs_done; epoch < config.train.epochs; ++epoch) {
    if (const int since = epochs_without_gain(config.train, run.state); since > 0) {
      if (run.root) {
        write_selection(config, run.state);  // epochs as asked now
        spdlog::info("stopping after epoch {} of {}: no lower validation error in {} epochs (train.patience {})",
                     run.state.epochs_done, config.train.epochs, since, config.train.patience);
      }
      break;
    }
    EpochSummary e = train_epoch(run, loader, optimizer, params, epoch);
    run.s.model->train(false);
    const Validation v = validate(run.s, run.group);
    e.val_error_mm = v.mm;
    run.validation_read = splits_read(run.s.dataset, config.data, v.read);
    keep_epoch(run, e, optimizer);
  }
  run.report.epochs_done = run.state.epochs_done;
  run.report.steps = run.state.steps;
  // No epoch ran now (e.g. train.epochs: 0): the checkpoints still exist,
  // so evaluating the untrained model works the same way.
  if (!run.root) return run.report;
  if (!std::filesystem::exists(run.report.last_checkpoint)) run.save("last", &optimizer);
  if (!std::filesystem::exists(run.report.best_checkpoint)) run.save("best", &optimizer);
  if (!std::filesystem::exists(std::filesystem::path(config.run.output) / data::run_layout::kSelection))
    write_selection(config, run.state);
  return run.report;
}

}  // namespace layers::train
