// `layers animate --config C --out DIR [--format glb|obj|pc2]...`: one
// scene from a generator config -- typically a user's own garments
// (outfit entries file:<mesh>, docs/own-data.md) on our body and a motion
// -- simulated and written as a one-sequence LAYERS-H5 dataset in
// DIR/data, then exported (default: one GLB) into DIR. The config's
// sequence count and splits are replaced by one scene in the train split;
// everything else is the config's. A scene the generator refuses (a
// garment inside the body, garments crossing, the validation limits) is
// one line and exit 1. An --out holding data/ already is refused (its
// scene may be of other garment files): nothing is replaced.
//
// With --model <experiment.yaml>, the trained model is rolled out on the
// simulated scene from its first two frames (the evaluator with the
// scene's dataset, normalised by the training dataset's statistics:
// DIR/model/ holds predictions.h5 and metrics.json, its error against the
// simulator) and the exports are of its prediction. Garment files or a
// body the training data did not hold are allowed; each is named in a
// note (generate/unseen.h).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "config_loading.h"
#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/export.h"
#include "layers/data/run_layout.h"
#include "layers/generate/generator.h"
#include "layers/generate/imported_garment.h"
#include "layers/generate/unseen.h"
#include "layers/metrics/registry.h"
#include "layers/train/evaluator.h"
#include "layers/train/session.h"
#include "plugins.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_animate(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand(
      "animate", "Simulate one scene of a config (e.g. your own garments) and export it (GLB, OBJ or PC2)");
  struct Args {
    std::string config, out;
    std::vector<std::string> sets, formats{"glb"};
    std::int64_t glb_chunk = data::kGlbFramesPerChunk;
    std::string model, checkpoint = "best";
    bool keep_refused = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--config", a->config, "generator config: body, motion, outfit (templates or file:<mesh>), wind")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", a->sets, "override a config value: --set key.path=value (repeatable)");
  cmd->add_option("--out", a->out, "output folder: data/ (LAYERS-H5) and the exports")->required();
  cmd->add_flag("--keep-refused", a->keep_refused,
                "a refused scene's frames into --out/refused/ (<id>.h5, <id>.refused.yaml, a GLB in glb/)");
  cmd->add_option("--format", a->formats, "export format: glb, obj or pc2 (repeatable)")->capture_default_str();
  cmd->add_option("--glb-chunk", a->glb_chunk, "glb: frames per chunk (as `layers export --glb-chunk`)")
      ->capture_default_str()
      ->check(CLI::Range(std::int64_t{2}, std::int64_t{100000}));
  cmd->add_option("--model", a->model,
                  "a trained model's experiment: roll it out on the simulated scene and export its prediction")
      ->check(CLI::ExistingFile);
  cmd->add_option("--checkpoint", a->checkpoint, "with --model: best, last, or a checkpoint file")
      ->capture_default_str();
  return [a]() {
    namespace fs = std::filesystem;
    std::vector<data::ExportFormat> formats;
    for (const std::string& f : a->formats) {
      const data::ExportFormat format = data::parse_export_format(f);
      if (std::find(formats.begin(), formats.end(), format) != formats.end())
        throw InputError("layers animate", "--format", "each format once", "'" + f + "' twice");
      formats.push_back(format);
    }
    std::vector<std::string> sets = a->sets;  // one scene, in the train split
    sets.insert(sets.end(), {"sequences=1", "splits.val=0", "splits.test=0", "splits.unseen_motions=[]",
                             "splits.unseen_outfits=[]"});
    const generate::GeneratorConfig config = generate::load_generator_config(a->config, sets);
    // The model, its checkpoint and its training statistics, before anything is simulated.
    std::optional<LoadedConfig> experiment;
    if (!a->model.empty()) {
      experiment = load_config(ConfigArgs{a->model, {}});
      const std::string checkpoint = train::resolve_checkpoint(experiment->typed, a->checkpoint);
      if (!fs::exists(checkpoint))
        throw InputError(a->model, "--checkpoint", "a trained model's checkpoint (layers train)",
                         "'" + checkpoint + "' (no such file)");
      train::open_session(experiment->typed, load_plugins().registry);  // the model, its dataset and stats.h5
    } else if (a->checkpoint != "best") {
      throw InputError("layers animate", "--checkpoint", "--model with it", "no --model");
    }
    generate::GenerateOptions options;
    options.out = (fs::path(a->out) / "data").string();
    if (fs::exists(options.out))
      throw InputError(a->out, "--out", "a new folder (each animate simulates its scene afresh)",
                       "a folder holding data/ from an earlier run");
    options.progress = false;
    const std::string refused_dir = (fs::path(a->out) / "refused").string();
    if (a->keep_refused) {
      if (fs::exists(refused_dir))
        throw InputError(a->out, "--keep-refused", "a folder without refused/ (from an earlier run)",
                         "'" + refused_dir + "'");
      options.keep_refused = refused_dir;
    }
    const generate::GenerateReport report =
        generate::generate_dataset(config, cfg::to_yaml(cfg::to_node(config)), options);
    if (report.written == 0) {
      // A refused scene does not use up --out: its data/ (made by this
      // run) goes, so the same command can run again.
      std::error_code ec;
      fs::remove_all(options.out, ec);
      std::string kept;
      if (a->keep_refused && fs::exists(refused_dir)) {
        for (const auto& e : fs::directory_iterator(refused_dir))
          if (e.path().extension() == ".h5") {
            const std::string id = e.path().stem().string();
            const data::Dataset refused = data::Dataset::open(e.path().string());
            const auto files = data::export_sequence(refused, id, data::ExportFormat::Glb, 0, -1,
                                                     (fs::path(refused_dir) / "glb").string(), a->glb_chunk);
            kept = "; its frames up to the one that broke a rule are in " + e.path().string() + " (" +
                   (fs::path(refused_dir) / (id + ".refused.yaml")).string() + " says what broke; " + files.front() +
                   " to look at)";
          }
      }
      throw InputError::message(
          a->config, "",
          "the scene was refused: " +
              (report.skip_reasons.empty() ? std::string("no reason given") : report.skip_reasons.front()) + kept +
              (a->keep_refused ? std::string() : " (--keep-refused keeps its frames to look at)"));
    }
    std::printf("%s: one scene simulated\n", options.out.c_str());
    const data::Dataset simulated = data::Dataset::open(options.out);
    const std::string id = simulated.ids().front();
    std::string exported = options.out;
    if (experiment) {
      for (const std::string& what : generate::unseen_in_training(config, experiment->typed.data.dataset))
        std::printf("note: the model never saw the %s in training (not in %s): its prediction is an extrapolation\n",
                    what.c_str(), experiment->typed.data.dataset.c_str());
      experiment->typed.eval.save_predictions = true;
      train::EvalOptions eval;
      eval.checkpoint = a->checkpoint;
      eval.sequences = {id};
      eval.horizon = 0;
      eval.dataset = options.out;
      eval.out_dir = (fs::path(a->out) / "model").string();
      eval.progress = false;
      const train::EvalReport r = train::run_evaluation(experiment->typed, load_plugins().registry, eval);
      std::printf("%s: %lld frames predicted, error %s mm against the simulator, %lld diverged\n", r.model.c_str(),
                  static_cast<long long>(r.frames), metrics::format(r.overall.at(metrics::kError)).c_str(),
                  static_cast<long long>(r.diverged));
      exported = (fs::path(r.out_dir) / data::run_layout::kPredictions).string();
      std::printf("written: %s (exported below)\n", exported.c_str());
    }
    const data::Dataset ds = data::Dataset::open(exported);
    for (std::size_t k = 0; k < formats.size(); ++k) {
      const std::string dir = (fs::path(a->out) / a->formats[k]).string();
      const auto files = data::export_sequence(ds, id, formats[k], 0, -1, dir, a->glb_chunk);
      std::printf("%s: %zu file%s (%s)\n", dir.c_str(), files.size(), files.size() == 1 ? "" : "s",
                  files.size() == 1 ? files.front().c_str() : a->formats[k].c_str());
    }
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
