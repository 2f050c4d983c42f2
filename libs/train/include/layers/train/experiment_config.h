// layers/train/experiment_config.h -- an experiment file: which data, which
// model, which losses, how to train and how to evaluate. `layers train`,
// `layers eval`, `layers rollout` and `layers config` read the same file.
// Torch-free.
//
//   run:   {seed: 0, threads: 2, device: cpu, output: runs/<name>}
//   data:  {dataset: data/tiny, train_split: train, val_split: val,
//           test_split: test, subsets: [], inner_only: false}
//   model: {name: layersnet, params: {...}}
//   loss:  {position: 1, normal: 1, body_collision: 1, layer_collision: 0,
//           collision_eps: 0.005}
//   train: {epochs: 10, batch_size: 4, lr: 0.001, ...}
//   eval:  {split: test, horizon: 35, diverge_mm: 1000, ...}
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/core/config.h"
#include "layers/core/run_config.h"

namespace layers::train {

struct DataConfig {
  std::string dataset;  // a dataset folder (layers generate)
  std::string train_split = "train", val_split = "val", test_split = "test";
  // Keep only sequences listed in at least one of these splits.yaml subsets
  // (e.g. [T, T+W]); empty = all.
  std::vector<std::string> subsets;
  bool inner_only = false;      // drop the outer garments (the paper's starred rows)
  bool allow_unhashed = false;  // read a dataset without recorded content hashes, unverified

  template <class V>
  void visit(V& v) {
    v("dataset", dataset, cfg::opt().help("dataset folder made by `layers generate`"));
    v("train_split", train_split);
    v("val_split", val_split);
    v("test_split", test_split);
    v("subsets", subsets, cfg::opt().help("only sequences in one of these splits.yaml subsets"));
    v("inner_only", inner_only, cfg::opt().help("train and evaluate on the inner garments only"));
    v("allow_unhashed", allow_unhashed,
      cfg::opt().help("read a dataset written before content hashes, unverified (docs/format.md, Integrity)"));
  }
};

// Weights of the shared loss terms (layers/zoo/losses.h); 0 switches a term off.
struct LossConfig {
  double position = 1.0, normal = 1.0, body_collision = 1.0, layer_collision = 0.0;
  double collision_eps = 0.005;    // metres
  std::string normals = "vertex";  // vertex (the paper's) | face

  template <class V>
  void visit(V& v) {
    v("position", position, cfg::opt().min(0).help("position MSE (m^2, scaled to cm^2)"));
    v("normal", normal,
      cfg::opt().min(0).help("normal MSE (unitless; 100 here is the paper's 1, docs/reproduction.md)"));
    v("normals", normals,
      cfg::opt()
          .choices({"vertex", "face"})
          .help("normal loss on area-weighted vertex normals (the paper's) or face normals"));
    v("body_collision", body_collision, cfg::opt().min(0).help("garment behind body surface"));
    v("layer_collision", layer_collision, cfg::opt().min(0).help("outer behind inner garment"));
    v("collision_eps", collision_eps, cfg::opt().range(0, 0.1).help("collision margin (m)"));
  }
};

struct TrainConfig {
  int epochs = 10;
  int batch_size = 4;         // windows (each one scene) per optimiser step
  int windows_per_epoch = 0;  // 0: every window of the split once
  int window_stride = 1;      // start frames of training windows, every n-th
  double lr = 1e-3;
  double lr_decay = 0.5;   // multiply the learning rate by this ...
  int lr_decay_every = 2;  // ... every n epochs
  double grad_clip = 1.0;  // max gradient norm; 0 = off
  bool two_step = true;    // loss on t+1 and t+2 (predicted t+1 fed back)
  int curriculum_max = 4;  // epoch k rolls min(k-1, this) steps without gradient first
  double noise_std = 0.0;  // m: Gaussian noise on each window's start positions (0 = off)
  int prefetch = 4;        // batches loaded ahead by the loader thread
  int val_horizon = 10;    // rollout length of the per-epoch validation
  int val_sequences = 8;   // sequences of the validation split used; 0 = all
  int patience = 0;        // stop after this many epochs without a lower validation error; 0 = off

  template <class V>
  void visit(V& v) {
    v("epochs", epochs, cfg::opt().range(0, 100000));
    v("batch_size", batch_size, cfg::opt().range(1, 4096));
    v("windows_per_epoch", windows_per_epoch, cfg::opt().min(0).help("0 = all windows"));
    v("window_stride", window_stride, cfg::opt().min(1));
    v("lr", lr, cfg::opt().range(0, 1));
    v("lr_decay", lr_decay, cfg::opt().range(0, 1));
    v("lr_decay_every", lr_decay_every, cfg::opt().min(1));
    v("grad_clip", grad_clip, cfg::opt().min(0));
    v("two_step", two_step);
    v("curriculum_max", curriculum_max, cfg::opt().range(0, 1000));
    v("noise_std", noise_std,
      cfg::opt().range(0, 0.1).help("m: noise added to the garment positions a window starts from (0 = off)"));
    v("prefetch", prefetch, cfg::opt().range(1, 64));
    v("val_horizon", val_horizon, cfg::opt().range(1, 100000));
    v("val_sequences", val_sequences, cfg::opt().min(0));
    v("patience", patience,
      cfg::opt().min(0).help("stop after this many epochs in a row without a lower validation error (0 = off)"));
  }
};

struct EvalConfig {
  std::string split;         // empty: data.test_split
  int horizon = 35;          // rollout frames; 0 = whole sequences
  double diverge_mm = 1000;  // a frame error above this (or non-finite) is divergence
  bool save_predictions = true;

  template <class V>
  void visit(V& v) {
    v("split", split, cfg::opt().help("split to evaluate (default data.test_split)"));
    v("horizon", horizon, cfg::opt().min(0).help("rollout frames; 0 = whole sequences"));
    v("diverge_mm", diverge_mm, cfg::opt().min(0).help("error bound marking divergence"));
    v("save_predictions", save_predictions, cfg::opt().help("write predictions.h5"));
  }
};

struct ExperimentConfig {
  RunConfig run;
  DataConfig data;
  cfg::Node model;  // checked by the zoo (zoo::create_model)
  LossConfig loss;
  TrainConfig train;
  EvalConfig eval;
  std::string source;  // the file it was read from (not a config key)

  template <class V>
  void visit(V& v) {
    v("run", run);
    v("data", data);
    v("model", model, cfg::opt().help("model name and parameters (see `layers models`)"));
    v("loss", loss);
    v("train", train);
    v("eval", eval);
  }
};

// Reads an experiment from a config tree (file + --set applied).
ExperimentConfig read_experiment(const cfg::Node& tree, const std::string& source);
// Loads `path`, applies `sets` (key.path=value) and reads it.
ExperimentConfig load_experiment(const std::string& path, const std::vector<std::string>& sets = {});

// The selection policy (docs/training.md, "Selection"): training reads
// data.train_split and the best checkpoint is chosen on data.val_split, so
// neither may be data.test_split. InputError naming config.source and the
// field otherwise. `layers train`, `layers eval` and every study
// (libs/study runs.cpp) check it before anything runs.
void check_selection(const ExperimentConfig& config);

// The split an evaluation or a benchmark reads: `requested` (a command
// line's --split), else eval.split, else data.test_split.
std::string evaluated_split(const ExperimentConfig& config, const std::string& requested = "");

}  // namespace layers::train
