// layers/core/run_config.h -- the `run:` section shared by every config
// (seed, threads, device, the data-parallel timeout): how a run executes, not what it computes.
#pragma once

#include <cstdint>
#include <string>

#include "layers/core/config.h"

namespace layers {

struct RunConfig {
  std::uint64_t seed = 0;
  int threads = 2;              // threads of the numeric work (train/compute_threads.h); 0 = all cores
  std::string device = "cpu";   // cpu or cuda
  std::string output = "runs";  // where runs write checkpoints, metrics, reports
  int dist_timeout_s = 60;      // data-parallel runs: longest wait for another rank (layers/dist)
  // Processes `layers train` runs as when the environment names no ranks
  // (docs/training.md): 0 = auto (`threads` ranks of one thread each when
  // threads >= 2 and they share train.batch_size evenly), 1 = one process.
  int ranks = 0;

  template <class V>
  void visit(V& v) {
    v("seed", seed, cfg::opt().help("random seed of the whole run"));
    v("threads", threads,
      cfg::opt().range(0, 256).help(
          "threads of the matrix products (OpenBLAS; torch's own operators use one); 0 = all cores"));
    v("device", device, cfg::opt().choices({"cpu", "cuda"}));
    v("output", output, cfg::opt().help("output folder"));
    v("dist_timeout_s", dist_timeout_s,
      cfg::opt().range(1, 86400).help("data-parallel runs: seconds to wait for another rank before failing"));
    v("ranks", ranks,
      cfg::opt().range(0, 256).help(
          "processes `layers train` starts for itself, sharing train.batch_size, one thread each (0 = auto: "
          "run.threads when it is 2 or more and divides the batch; 1 = one process with run.threads threads)"));
  }
};

}  // namespace layers
