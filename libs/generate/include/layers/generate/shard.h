// layers/generate/shard.h -- which shards of a dataset one `layers
// generate` process makes: `--shard k/n` (shards j with j % n == k), or
// `--shard auto[/n]`, where k and n come from a batch scheduler's
// environment (a Slurm array job, a Kubernetes Indexed Job). Also the
// one-line list of shard numbers that messages print.
//
// `auto` reads the index from SLURM_ARRAY_TASK_ID (Slurm) or
// JOB_COMPLETION_INDEX (Kubernetes), exactly one of them, and the count
// from every source that gives one: the `/n` of `auto/n`,
// LAYERS_SHARD_COUNT and SLURM_ARRAY_TASK_COUNT; at least one must, and
// all that do must agree. A Slurm array must be numbered 0..n-1 (checked
// with SLURM_ARRAY_TASK_MIN/MAX when Slurm sets them). Every problem is a
// UsageError (exit 2) of one line.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace layers::generate {

// Environment variables by name; only the names below are read.
using Environment = std::map<std::string, std::string>;

// SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_COUNT, SLURM_ARRAY_TASK_MIN,
// SLURM_ARRAY_TASK_MAX, JOB_COMPLETION_INDEX, LAYERS_SHARD_COUNT.
const std::vector<std::string>& shard_environment_names();

// Those of shard_environment_names() that are set in this process.
Environment shard_environment();

struct ShardChoice {
  int index = 0;       // k
  int count = 1;       // n
  std::string source;  // where k and n came from ("--shard", or the variables read)
};

// Parses a --shard value: "k/n" with 0 <= k < n, "auto" or "auto/n";
// `env` is consulted for auto only.
ShardChoice parse_shard(const std::string& text, const Environment& env = {});

// Shard numbers as one short list, runs of three or more as ranges:
// {1, 2} -> "1, 2", {3, 4, 5, 6, 7, 9} -> "3-7, 9". `shards` ascending.
std::string shard_list(const std::vector<int>& shards);

}  // namespace layers::generate
