// apps/layers/dist_join.h -- how `layers train` and `layers eval` join a
// data-parallel run: the group the environment names (layers/dist/env.h:
// torchrun's, Slurm's or `layers launch`'s variables), with the
// experiment's run.dist_timeout_s; ranks other than 0 then log warnings
// and errors only (rank 0 alone logs, prints and writes).
#pragma once

#include <memory>

#include "layers/dist/group.h"
#include "layers/train/experiment_config.h"

namespace layers::app {

// Null when the environment names no distributed run (one process, as always).
std::unique_ptr<dist::Group> join_group(const train::ExperimentConfig& config);

}  // namespace layers::app
