// apps/layers/rank_launch.h -- starting N copies of this binary as the
// ranks of one data-parallel run on this machine, with the environment
// torchrun would give them (RANK, WORLD_SIZE, LOCAL_RANK,
// LOCAL_WORLD_SIZE, MASTER_ADDR=127.0.0.1, MASTER_PORT), waiting for them,
// and stopping the others when one fails (SIGTERM, SIGKILL after a grace
// period). Ranks stop when the launcher dies (PR_SET_PDEATHSIG); SIGINT
// and SIGTERM are forwarded. Used by `layers launch` and by `layers train`
// when it starts its own ranks (run.ranks).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace layers::app {

struct RankLaunch {
  int ranks = 2;
  int port = 0;                   // 0: a free port on 127.0.0.1
  int grace_s = 10;               // seconds the others get after one failed
  std::vector<std::string> args;  // after the binary's path: global options, the verb and its arguments
  std::vector<std::pair<std::string, std::string>> env;  // set in every rank besides torchrun's
};

// Runs the ranks and returns the first non-zero exit code (128 + signal
// for a rank killed by one), 0 when all succeeded. `verb` names the caller
// in messages.
int launch_ranks(const RankLaunch& launch, const std::string& verb);

}  // namespace layers::app
