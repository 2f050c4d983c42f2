// `layers generate`: a LAYERS dataset folder from a generator config
// (configs/data/*.yaml): resumable, shardable across processes, threaded.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <tuple>

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/generate/generator.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_generate(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("generate", "Generate a LAYERS dataset (simulated garments on moving bodies)");
  struct Args {
    std::string config, out, shard = "0/1";
    std::vector<std::string> sets;
    int threads = 1;
    bool quiet = false, print_config = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--config", a->config, "generator config (configs/data/<name>.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", a->sets, "override a config value: --set key.path=value (repeatable)");
  cmd->add_option("--out", a->out, "dataset folder (default data/<name>)");
  cmd->add_option("--shard", a->shard, "generate only shards j with j % n == k: k/n")->capture_default_str();
  cmd->add_option("--threads", a->threads, "scenes simulated in parallel")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  cmd->add_flag("--quiet", a->quiet, "no progress line");
  cmd->add_flag("--print-config", a->print_config, "print the resolved config (it is always saved as generator.yaml)");
  return [a]() {
    cfg::Node tree = cfg::load_file(a->config);
    for (const auto& s : a->sets) cfg::apply_set(tree, s);
    // The file holds the generator config at its top level.
    auto config = cfg::read<generate::GeneratorConfig>(tree);
    generate::check(config, a->config);
    const std::string resolved = cfg::to_yaml(cfg::to_node(config));
    generate::GenerateOptions options;
    options.out = a->out.empty() ? "data/" + config.name : a->out;
    std::tie(options.shard_index, options.shard_count) = generate::parse_shard(a->shard);
    options.threads = a->threads;
    options.progress = !a->quiet;
    if (a->print_config) std::printf("%s", resolved.c_str());
    std::printf("resolved config: %s/generator.yaml\n", options.out.c_str());
    std::fflush(stdout);
    auto report = generate::generate_dataset(config, resolved, options);
    std::printf("%s: %d scenes in shard %s: %d simulated now (%d written, %d skipped), %d finished before\n",
                options.out.c_str(), report.scenes, a->shard.c_str(), report.simulated, report.written, report.skipped,
                report.reused);
    if (report.simulated_frames > 0)
      std::printf("simulation: %d frames, %.3f s per frame (per thread; %.3f s CPU), wall %.1f s\n",
                  report.simulated_frames, report.simulate_seconds / report.simulated_frames,
                  report.simulate_cpu_seconds / report.simulated_frames, report.seconds);
    for (const auto& r : report.skip_reasons) std::printf("skipped %s\n", r.c_str());
    std::printf(report.finalized ? "dataset complete: dataset.yaml, splits.yaml, stats.h5 written\n"
                                 : "dataset not complete yet: other shards are missing\n");
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
