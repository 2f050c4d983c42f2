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
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/export.h"
#include "layers/generate/generator.h"
#include "layers/generate/imported_garment.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_animate(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand(
      "animate", "Simulate one scene of a config (e.g. your own garments) and export it (GLB, OBJ or PC2)");
  struct Args {
    std::string config, out;
    std::vector<std::string> sets, formats{"glb"};
    std::int64_t glb_chunk = data::kGlbFramesPerChunk;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--config", a->config, "generator config: body, motion, outfit (templates or file:<mesh>), wind")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", a->sets, "override a config value: --set key.path=value (repeatable)");
  cmd->add_option("--out", a->out, "output folder: data/ (LAYERS-H5) and the exports")->required();
  cmd->add_option("--format", a->formats, "export format: glb, obj or pc2 (repeatable)")->capture_default_str();
  cmd->add_option("--glb-chunk", a->glb_chunk, "glb: frames per chunk (as `layers export --glb-chunk`)")
      ->capture_default_str()
      ->check(CLI::Range(std::int64_t{2}, std::int64_t{100000}));
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
    generate::GenerateOptions options;
    options.out = (fs::path(a->out) / "data").string();
    if (fs::exists(options.out))
      throw InputError(a->out, "--out", "a new folder (each animate simulates its scene afresh)",
                       "a folder holding data/ from an earlier run");
    options.progress = false;
    const generate::GenerateReport report =
        generate::generate_dataset(config, cfg::to_yaml(cfg::to_node(config)), options);
    if (report.written == 0)
      throw InputError::message(
          a->config, "",
          "the scene was refused: " +
              (report.skip_reasons.empty() ? std::string("no reason given") : report.skip_reasons.front()));
    std::printf("%s: one scene simulated\n", options.out.c_str());
    const data::Dataset ds = data::Dataset::open(options.out);
    const std::string id = ds.ids().front();
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
