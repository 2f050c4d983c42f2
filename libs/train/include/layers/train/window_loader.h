// layers/train/window_loader.h -- training windows streamed from a
// LAYERS-H5 dataset (layers/data Dataset) into model tensors, shuffled per
// epoch with the run's seed, in batches, read ahead by one loader thread.
//
// A window is frames [start - history, start + horizon] of one sequence;
// a batch is a list of windows (scenes may differ in vertex counts: the
// trainer steps each scene and averages their losses, so no padding is
// needed). Memory stays bounded: at most `prefetch` batches wait in the
// queue, and converted static data sits in a small LRU cache. Order is
// deterministic for a seed and epoch (one producer, FIFO queue).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "layers/data/dataset.h"
#include "layers/train/scene_tensors.h"

namespace layers::train {

struct LoaderOptions {
  std::string split = "train";
  std::vector<std::string> subsets;  // empty: the whole split
  GarmentSelection selection;
  std::int64_t history = 1;
  int batch_size = 4;
  int windows_per_epoch = 0;  // 0: all windows
  int stride = 1;             // window start frames: every n-th
  int prefetch = 4;           // batches read ahead
  std::uint64_t seed = 0;
  std::size_t static_cache = 16;  // converted sequences kept
  // Data-parallel share: of the epoch's shuffled windows (the same order on
  // every rank), cut to a multiple of `world`, this rank reads every
  // world-th from `rank` on, so its k-th batch holds its windows of the
  // k-th batch of batch_size * world windows one process would read.
  int rank = 0, world = 1;
};

struct Sample {
  std::shared_ptr<const zoo::SequenceStatic> statics;
  FrameTensors frames;  // history + horizon + 1 rows
  std::string id;
  std::int64_t start = 0;  // absolute frame of row `history`
};
using Batch = std::vector<Sample>;

// The ids of `split` that belong to one of `subsets` (all when empty);
// InputError naming splits.yaml if a split or subset is missing.
std::vector<std::string> select_sequences(const data::Dataset& dataset, const std::string& split,
                                          const std::vector<std::string>& subsets);

// One window: a sequence and the absolute frame of its row `history`.
struct WindowRef {
  std::string id;
  std::int64_t start = 0;
};

// Every window of `sequences` with this horizon, in sequence order: starts
// history, history + stride, ... while start + horizon < n_frames.
std::vector<WindowRef> all_windows(const data::Dataset& dataset, const std::vector<std::string>& sequences,
                                   const LoaderOptions& options, std::int64_t horizon);
// The windows of one epoch in the order WindowLoader reads them (and the
// Python package's WindowDataset, docs/python.md): all_windows shuffled
// for options.seed and `epoch`, cut to windows_per_epoch, then this rank's
// share. Throws InputError when no sequence is long enough, or a rank
// would get no window.
std::vector<WindowRef> epoch_windows(const data::Dataset& dataset, const std::vector<std::string>& sequences,
                                     const LoaderOptions& options, int epoch, std::int64_t horizon);

class WindowLoader {
 public:
  // `dataset` must outlive the loader.
  WindowLoader(const data::Dataset& dataset, LoaderOptions options);
  ~WindowLoader();
  WindowLoader(const WindowLoader&) = delete;
  WindowLoader& operator=(const WindowLoader&) = delete;

  const std::vector<std::string>& sequences() const;
  // Windows with this horizon in the selected sequences.
  std::size_t windows(std::int64_t horizon) const;

  // Shuffles for `epoch` and starts reading ahead windows with `horizon`
  // frames after the start; returns the number of batches of the epoch.
  // Throws InputError if no sequence is long enough.
  std::size_t start_epoch(int epoch, std::int64_t horizon);
  // The next batch of the epoch (nullopt at its end); rethrows an error
  // of the loader thread.
  std::optional<Batch> next();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace layers::train
