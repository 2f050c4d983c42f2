// op_profile.h (private) -- where a model's time goes: runs a step under
// LibTorch's profiler and sums it by phase and by operator. A phase is a
// scope named "phase:<name>" (RECORD_USER_SCOPE in the models, the loss
// and backward of the training step); each operator's own time goes to
// its innermost phase (operators of the backward pass to "backward",
// those outside every phase to "other"). Also measures the matrix-product
// peak of this machine for the same thread count, to compare with.
#pragma once

#include <ATen/ATen.h>

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace layers::train {

struct OpTotals {
  double ms = 0;     // own time (children excluded), per step
  double calls = 0;  // per step
  double gflop = 0;  // counted by the profiler (matrix products, convolutions, element-wise adds and products)
};

struct StepProfile {
  int steps = 0;                                                     // profiled steps (figures are per step)
  double ms = 0;                                                     // wall time per step
  std::map<std::string, OpTotals> phases;                            // by phase
  std::map<std::string, OpTotals> ops;                               // by operator name
  std::map<std::string, std::map<std::string, OpTotals>> phase_ops;  // by phase, then operator
  double allocated_mb = 0;  // bytes the step allocates (sum of allocations), MiB
  double allocations = 0;   // number of allocations per step
  // The profiler's flop count over the time of the operators that have
  // one (mm, addmm, bmm, matmul, ...), and over the whole step.
  double matmul_gflops = 0, step_gflops = 0;
};

// Runs `step` `warmup` times unprofiled, then `steps` times profiled.
StepProfile profile_steps(const std::function<void()>& step, int steps, int warmup = 1);

// Single-precision matrix-product rate (GFLOP/s) of an n x n product with
// the current torch thread count, best of a few repetitions.
double matmul_peak_gflops(std::int64_t n = 1024);

// The phases with their ms per step, largest first.
std::vector<std::pair<std::string, double>> phase_list(const StepProfile& p);

// The profile as JSON: totals, phases (largest first), the `top` operators
// by own time.
nlohmann::ordered_json to_json(const StepProfile& p, std::size_t top = 12);

}  // namespace layers::train
