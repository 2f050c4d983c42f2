// `layers generate`: a LAYERS dataset folder from a generator config
// (configs/data/*.yaml): resumable, shardable across processes (--shard
// k/n, or auto from a Slurm array or Kubernetes Indexed Job), threaded;
// `--finalize` writes the dataset's manifest, splits and statistics once
// every shard exists (docs/cluster.md).
#include <spdlog/spdlog.h>

#include <cstdio>

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/generate/generator.h"
#include "layers/generate/imported_garment.h"
#include "layers/generate/shard.h"
#include "output_folder.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_generate(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("generate", "Generate a LAYERS dataset (simulated garments on moving bodies)");
  struct Args {
    std::string config, out, shard = "0/1", keep_refused;
    std::vector<std::string> sets;
    int threads = 1;
    bool quiet = false, print_config = false, finalize = false, no_finalize = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--config", a->config, "generator config (configs/data/<name>.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", a->sets, "override a config value: --set key.path=value (repeatable)");
  cmd->add_option("--out", a->out, "dataset folder (default data/<name>)");
  auto* shard = cmd->add_option("--shard", a->shard,
                                "generate only shards j with j % n == k: k/n, or auto[/n] (k and n from "
                                "SLURM_ARRAY_TASK_ID/COUNT or JOB_COMPLETION_INDEX with LAYERS_SHARD_COUNT)")
                    ->capture_default_str();
  auto* threads = cmd->add_option("--threads", a->threads, "scenes simulated in parallel")
                      ->capture_default_str()
                      ->check(CLI::Range(1, 256));
  auto* no_finalize = cmd->add_flag("--no-finalize", a->no_finalize,
                                    "leave dataset.yaml, splits.yaml and stats.h5 to a later --finalize (array jobs)");
  cmd->add_flag("--finalize", a->finalize,
                "only write dataset.yaml, splits.yaml and stats.h5, once every shard exists (exit 1 naming the "
                "missing shards otherwise)")
      ->excludes(shard)
      ->excludes(threads)
      ->excludes(no_finalize);
  cmd->add_flag("--quiet", a->quiet, "no progress line");
  cmd->add_option("--keep-refused", a->keep_refused,
                  "folder for refused scenes: <id>.h5 (their recorded frames, up to the one that broke a rule) and "
                  "<id>.refused.yaml (what broke); never replaces a file");
  cmd->add_flag("--print-config", a->print_config, "print the resolved config (it is always saved as generator.yaml)");
  return [a]() {
    // The file holds the generator config at its top level.
    const generate::GeneratorConfig config = generate::load_generator_config(a->config, a->sets);
    const std::string resolved = cfg::to_yaml(cfg::to_node(config));
    generate::GenerateOptions options;
    options.out = a->out.empty() ? "data/" + config.name : a->out;
    if (a->print_config) std::printf("%s", resolved.c_str());
    if (a->finalize) {
      const generate::FinalizeReport fin = generate::finalize_dataset(config, resolved, options.out);
      if (!fin.done())
        throw InputError::message(
            options.out, "",
            "shards missing: " + generate::shard_list(fin.missing) + " (of " + std::to_string(fin.shards) + ")");
      std::printf("%s: dataset complete: %d shards, %lld sequences, %lld frames; dataset.yaml, splits.yaml%s written\n",
                  options.out.c_str(), fin.shards, static_cast<long long>(fin.sequences),
                  static_cast<long long>(fin.frames), fin.stats ? ", stats.h5" : " (no train split: no stats.h5)");
      return static_cast<int>(kOk);
    }
    const generate::ShardChoice choice = generate::parse_shard(a->shard, generate::shard_environment());
    options.shard_index = choice.index;
    options.shard_count = choice.count;
    options.threads = a->threads;
    options.progress = !a->quiet;
    if (!a->keep_refused.empty()) {
      if (same_or_inside(a->keep_refused, options.out) || same_or_inside(options.out, a->keep_refused))
        throw InputError("layers generate", "--keep-refused", "a folder apart from the dataset folder --out",
                         "'" + a->keep_refused + "'");
      options.keep_refused = a->keep_refused;
    }
    options.finalize = !a->no_finalize;
    const std::string shard_text = std::to_string(choice.index) + "/" + std::to_string(choice.count);
    if (choice.source != "--shard") spdlog::info("--shard {}: shard {} from {}", a->shard, shard_text, choice.source);
    generate::check_output_folder(options.out);
    std::printf("resolved config: %s/generator.yaml\n", options.out.c_str());
    std::fflush(stdout);
    auto report = generate::generate_dataset(config, resolved, options);
    const std::string cut =
        config.window_min_frames > 0 ? " (" + std::to_string(report.cut) + " cut to a clean window)" : "";
    std::printf("%s: %d scenes in shard %s: %d simulated now (%d written%s, %d skipped), %d finished before\n",
                options.out.c_str(), report.scenes, shard_text.c_str(), report.simulated, report.written, cut.c_str(),
                report.skipped, report.reused);
    if (report.simulated_frames > 0)
      std::printf("simulation: %d frames, %.3f s per frame (per thread; %.3f s CPU), wall %.1f s\n",
                  report.simulated_frames, report.simulate_seconds / report.simulated_frames,
                  report.simulate_cpu_seconds / report.simulated_frames, report.seconds);
    for (const auto& r : report.skip_reasons) std::printf("skipped %s\n", r.c_str());
    if (report.finalized)
      std::printf("dataset complete: dataset.yaml, splits.yaml%s written\n",
                  report.stats ? ", stats.h5" : " (no train split: no stats.h5)");
    else if (options.finalize)
      std::printf("dataset not complete yet: other shards are missing\n");
    else
      std::printf(
          "not finalized (--no-finalize): run `layers generate --finalize` with the same --config, --set "
          "and --out once every shard exists\n");
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
