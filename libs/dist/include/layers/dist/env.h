// layers/dist/env.h -- where a data-parallel process stands, read from
// the environment exactly as torchrun and Slurm set it (torch-free).
//
//   torchrun / `layers launch`: RANK, WORLD_SIZE, LOCAL_RANK, MASTER_ADDR,
//                               MASTER_PORT
//   Slurm (srun):               SLURM_PROCID, SLURM_NTASKS, SLURM_LOCALID;
//                               MASTER_ADDR, else the first node of
//                               SLURM_JOB_NODELIST; MASTER_PORT, else
//                               29500 + SLURM_JOB_ID % 10000
// WORLD_SIZE wins over Slurm's variables when both are set. Neither set,
// or a world of one: no distributed run (nullopt), so a plain process
// behaves exactly as before. A bad value is an InputError naming
// "environment", the variable, what was expected and what was found.
#pragma once

#include <functional>
#include <optional>
#include <string>

namespace layers::dist {

struct DistEnv {
  int rank = 0, world_size = 1, local_rank = 0;
  std::string master_addr;
  int master_port = 0;
  std::string launcher;  // "torchrun" (RANK/WORLD_SIZE) or "slurm"
};

// Looks variables up through `get` (nullptr: unset), so tests need not
// touch the process environment.
using EnvLookup = std::function<const char*(const char*)>;
std::optional<DistEnv> read_env(const EnvLookup& get);
std::optional<DistEnv> read_env();  // the process environment

// The first host of a Slurm node list: "node[01-04,07],gpu3" -> "node01",
// "a[1-2]-ib[5]" -> "a1-ib5". InputError naming `field` for an empty list
// or unbalanced brackets.
std::string first_node(const std::string& nodelist, const std::string& field = "SLURM_JOB_NODELIST");

}  // namespace layers::dist
