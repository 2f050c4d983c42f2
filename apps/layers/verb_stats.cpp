// `layers stats`: normalisation statistics of a dataset from its train
// split, written to <dataset>/stats.h5 (or --out) and printed.
#include <cstdio>
#include <filesystem>

#include "dataset_access.h"
#include "layers/data/dataset.h"
#include "layers/data/stats.h"
#include "output_folder.h"
#include "verbs.h"

namespace layers::app {
namespace {
void print_moments(const char* name, const data::Moments& m) {
  std::printf("  %-22s mean % .6f % .6f % .6f   std %.6f %.6f %.6f\n", name, m.mean[0], m.mean[1], m.mean[2], m.std[0],
              m.std[1], m.std[2]);
}
}  // namespace

VerbRun register_stats(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("stats", "Compute normalisation statistics (train split only) into stats.h5");
  struct Args {
    bool allow_unhashed = false;
    std::string path, out, split = "train";
    bool dry_run = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("dataset", args->path, "dataset folder")->required();
  add_allow_unhashed(*cmd, args->allow_unhashed);
  cmd->add_option("--split", args->split, "split to compute from")->capture_default_str();
  cmd->add_option("--out", args->out, "output file (default <dataset>/stats.h5)");
  cmd->add_flag("--print-only", args->dry_run, "print the statistics without writing them");
  return [args]() {
    if (!args->dry_run && !args->out.empty()) claim_new_output(args->out, "--out", {args->path});
    data::Dataset ds = open_dataset(args->path, args->allow_unhashed);
    data::StatsOptions options;
    options.split = args->split;
    data::NormStats stats = data::compute_stats(ds, options);
    std::printf("statistics of split '%s': %lld sequences, %lld frames (root-relative, per frame)\n",
                stats.split.c_str(), static_cast<long long>(stats.n_sequences), static_cast<long long>(stats.n_frames));
    std::printf("  (positions in m, velocities in m/frame, accelerations in m/frame^2)\n");
    data::for_each_quantity(stats, print_moments);
    if (!args->dry_run) {
      std::string out = args->out.empty() ? (std::filesystem::path(args->path) / "stats.h5").string() : args->out;
      if (args->out.empty() && std::filesystem::is_directory(args->path))
        data::write_dataset_stats(args->path, stats);  // records its hash in dataset.yaml
      else
        data::write_stats(out, stats);
      std::printf("wrote %s\n", out.c_str());
    }
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
