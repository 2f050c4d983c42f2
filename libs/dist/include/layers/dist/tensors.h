// layers/dist/tensors.h -- the tensor collectives of data-parallel
// training: the same starting parameters on every rank, and gradients
// averaged over the ranks before the optimiser step.
#pragma once

#include <ATen/core/Tensor.h>

#include <vector>

namespace layers::dist {

class Group;

// Overwrites `tensors` on every rank with rank 0's values (no gradient).
void broadcast_from_root(Group& group, const std::vector<at::Tensor>& tensors);

// Sums every parameter's gradient over the ranks and divides by the world
// size, in one collective; a parameter without a gradient on one rank
// counts as zero there, and keeps none where no rank has one. `sums` is
// summed over the ranks in the same exchange (e.g. the batch losses).
void average_gradients(Group& group, const std::vector<at::Tensor>& params, std::vector<double>& sums);

}  // namespace layers::dist
