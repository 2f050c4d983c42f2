// `layers train <experiment.yaml>`: train the experiment's model (see
// libs/train/include/layers/train/trainer.h). A run folder that already
// holds a run is continued only with --resume, or moved aside (never
// deleted) with --force; the model is checked before the folder is touched.
// Data-parallel when the environment names ranks (dist_join.h, `layers
// launch`): every rank checks the same things, rank 0 alone touches the
// folder and prints. Otherwise it may start its own ranks (run.ranks),
// which share each batch.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>

#include "config_loading.h"
#include "dist_join.h"
#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/data/run_layout.h"
#include "layers/dist/env.h"
#include "layers/train/trainer.h"
#include "layers/zoo/model_config.h"
#include "output_folder.h"
#include "plugins.h"
#include "rank_launch.h"
#include "verbs.h"

namespace layers::app {
namespace {

namespace fs = std::filesystem;

// What in `dir` shows a run was made there: checkpoints, evaluations, a
// benchmark. Empty for a new or empty folder.
std::vector<std::string> run_results_in(const fs::path& dir) {
  std::vector<std::string> found;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return found;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (data::run_layout::is_result(name)) found.push_back(name);
  }
  std::sort(found.begin(), found.end());
  return found;
}

// Set in the ranks `layers train` starts for itself: how many share the
// experiment's batch.
constexpr const char* kSharedBatch = "LAYERS_SHARED_BATCH";

// The ranks this command starts for itself (run.ranks), 0 when it runs as
// it is: the environment already names ranks (layers launch, torchrun,
// srun), it is one of them, or one process is asked for.
int own_ranks(const train::ExperimentConfig& c, const std::string& file) {
  if (dist::read_env() || std::getenv(kSharedBatch)) return 0;
  const int batch = c.train.batch_size;
  if (c.run.ranks == 0) {
    if (c.run.threads < 2) return 0;
    if (batch % c.run.threads == 0) return c.run.threads;
    spdlog::info("one process with {} threads: train.batch_size {} is not shared evenly by {} ranks (run.ranks)",
                 c.run.threads, batch, c.run.threads);
    return 0;
  }
  if (c.run.ranks > 1 && batch % c.run.ranks != 0)
    throw InputError(file, "run.ranks",
                     "a number of ranks that shares train.batch_size (" + std::to_string(batch) + ") evenly",
                     std::to_string(c.run.ranks));
  return c.run.ranks > 1 ? c.run.ranks : 0;
}

// In a rank started by own_ranks(): its share of the batch, one thread.
void take_share(train::ExperimentConfig& c) {
  const char* shared = std::getenv(kSharedBatch);
  if (!shared) return;
  const std::optional<dist::DistEnv> env = dist::read_env();
  if (!env || std::to_string(env->world_size) != shared)
    throw InputError("environment", kSharedBatch, "the world size of the ranks `layers train` started",
                     std::string("'") + shared + "'");
  c.train.batch_size /= env->world_size;
  c.run.threads = 1;
}

}  // namespace

VerbRun register_train(CLI::App& app, const Global& global) {
  auto* cmd = app.add_subcommand("train", "Train the model of an experiment config (configs/experiments/*.yaml)");
  struct Args {
    ConfigArgs config;
    bool resume = false, force = false, quiet = false;
  };
  auto a = std::make_shared<Args>();
  add_config_options(*cmd, a->config, /*required=*/true);
  auto* resume = cmd->add_flag("--resume", a->resume, "continue from <run.output>/checkpoint-last.pt if it exists");
  cmd->add_flag("--force", a->force,
                "start afresh in a run.output that holds a run: the old folder is moved aside to "
                "<run.output>.replaced-<time>, never deleted")
      ->excludes(resume);
  cmd->add_flag("--quiet", a->quiet, "no progress line");
  return [a, &global]() {
    LoadedConfig loaded = load_config(a->config);
    take_share(loaded.typed);
    // Everything that can be checked before the run folder is touched: a
    // failing command leaves it as it was.
    train::check_selection(loaded.typed);
    zoo::create_model(load_plugins().registry, loaded.typed.model);
    {
      std::error_code ec;
      if (!loaded.typed.data.dataset.empty() && !fs::exists(loaded.typed.data.dataset, ec))
        throw InputError(a->config.file, "data.dataset", "a dataset folder (made by `layers generate`) or shard file",
                         "'" + loaded.typed.data.dataset + "' (no such folder or file)");
    }
    if (const int ranks = own_ranks(loaded.typed, a->config.file)) {
      // The same command as `ranks` processes of one thread, each taking
      // its share of every batch: the steps of one process (the windows
      // cut to a multiple of the ranks).
      RankLaunch launch;
      launch.ranks = ranks;
      launch.args = {"--log-level", global.log_level, "train", a->config.file};
      for (const std::string& s : a->config.sets) launch.args.insert(launch.args.end(), {"--set", s});
      if (a->resume) launch.args.push_back("--resume");
      if (a->force) launch.args.push_back("--force");
      if (a->quiet) launch.args.push_back("--quiet");
      launch.env = {{kSharedBatch, std::to_string(ranks)}};
      spdlog::info("training as {} ranks of one thread each, {} windows of every batch each (run.ranks)", ranks,
                   loaded.typed.train.batch_size / ranks);
      return launch_ranks(launch, "train");
    }
    const std::unique_ptr<dist::Group> group = join_group(loaded.typed);
    const bool root = !group || group->is_root();
    const fs::path out = loaded.typed.run.output;
    const std::vector<std::string> held = run_results_in(out);
    if (!held.empty() && !a->resume && !a->force)
      throw InputError(out.string(), "run.output",
                       "a new or empty run folder (--resume continues the run there, --force moves it aside)",
                       "a folder holding a run (" + held.front() + (held.size() > 1 ? ", ..." : "") + ")");
    if (group) group->barrier();  // every rank has looked at the folder before rank 0 changes it
    if (root && !held.empty() && a->force) {
      const fs::path aside = move_aside(out, "run.output");
      std::printf("moved the old run %s aside to %s\n", out.string().c_str(), aside.string().c_str());
    }
    train::TrainOptions options;
    // The resolved experiment is written once the model and, on --resume,
    // its checkpoint agree: a resume that fails leaves the run's
    // experiment.yaml as it was.
    options.started = [&] {
      fs::create_directories(out);
      write_text_atomic((out / data::run_layout::kExperiment).string(), cfg::to_yaml(loaded.resolved));
    };
    options.resume = a->resume;
    options.progress = !a->quiet;
    options.group = group.get();
    const train::TrainReport r = train::run_training(loaded.typed, load_plugins().registry, options);
    if (!root) return static_cast<int>(kOk);
    std::printf("trained %d epochs (%lld steps), %lld trainable parameters\n", r.epochs_done,
                static_cast<long long>(r.steps), static_cast<long long>(r.trainable_parameters));
    for (const auto& e : r.epochs) {
      const auto share = [&](double part) {
        return std::to_string(static_cast<int>(std::lround(100.0 * part / std::max(e.seconds, 1e-9)))) + "%";
      };
      const std::string ranks =
          e.ranks > 1 ? " on " + std::to_string(e.ranks) + " ranks, " + share(e.comm_seconds) + " in gradient exchange"
                      : "";
      std::printf(
          "  epoch %d: loss %.5g  val error %.2f mm  %.1f frames/s  %.1f s%s (data %s, optimiser %s)  peak memory %.0f "
          "MiB\n",
          e.epoch, e.loss, e.val_error_mm, e.frames_per_second, e.seconds, ranks.c_str(), share(e.data_seconds).c_str(),
          share(e.optimizer_seconds).c_str(), e.peak_resident_mib);
    }
    std::printf("checkpoints: %s, %s\n", r.last_checkpoint.c_str(), r.best_checkpoint.c_str());
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
