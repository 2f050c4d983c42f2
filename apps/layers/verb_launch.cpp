// `layers launch --nproc N -- <verb> <args...>`: a data-parallel run on one
// machine: N copies of this binary as its ranks (rank_launch.h; a free
// port unless --master-port), exiting with the failed rank's code.
#include <string>
#include <vector>

#include "layers/core/error.h"
#include "rank_launch.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_launch(CLI::App& app, const Global& global) {
  auto* cmd = app.add_subcommand(
      "launch", "Run a data-parallel `train` or `eval` as N processes on this machine (docs/training.md)");
  struct Args {
    int nproc = 2;
    int port = 0;
    int grace_s = 10;
    std::vector<std::string> command;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--nproc", a->nproc, "processes (ranks) to start")->check(CLI::Range(1, 1024))->capture_default_str();
  cmd->add_option("--master-port", a->port, "rendezvous port on 127.0.0.1 (default: a free one)")
      ->check(CLI::Range(1, 65535));
  cmd->add_option("--grace", a->grace_s, "seconds the other ranks get to stop after one failed, before SIGKILL")
      ->check(CLI::Range(0, 3600))
      ->capture_default_str();
  cmd->add_option("command", a->command, "the layers verb and its arguments, after --, e.g. -- train exp.yaml")
      ->required();
  cmd->footer("Example: layers launch --nproc 2 -- train configs/experiments/layersnet_tiny.yaml");
  return [a, &global]() {
    if (a->command.front() == "launch") throw UsageError("launch: the command after -- is a verb other than launch");
    RankLaunch launch;
    launch.ranks = a->nproc;
    launch.port = a->port;
    launch.grace_s = a->grace_s;
    launch.args = {"--log-level", global.log_level};
    launch.args.insert(launch.args.end(), a->command.begin(), a->command.end());
    return launch_ranks(launch, "launch");
  };
}

}  // namespace layers::app
