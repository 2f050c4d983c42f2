// `layers export`: a sequence's meshes as OBJ (one file per frame), PC2
// (one point cache per mesh) or one glTF binary, for Blender and others.
#include <cstdio>

#include "dataset_access.h"
#include "frame_range.h"
#include "layers/data/dataset.h"
#include "layers/data/export.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_export(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("export", "Export a sequence's body and garments as OBJ, PC2 or glTF (GLB)");
  struct Args {
    bool allow_unhashed = false;
    std::string path, sequence, format = "obj", frames = ":", out = "export";
    std::int64_t glb_chunk = data::kGlbFramesPerChunk;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("dataset", args->path, "dataset folder or shard .h5 file")->required();
  add_allow_unhashed(*cmd, args->allow_unhashed);
  cmd->add_option("sequence", args->sequence, "sequence id")->required();
  cmd->add_option("--format", args->format, "obj, pc2 or glb")->capture_default_str();
  cmd->add_option("--frames", args->frames, "frames a:b (b excluded), a:, :b or a single frame")->capture_default_str();
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--glb-chunk", args->glb_chunk,
                  "glb: frames per chunk (each mesh's frames are morph targets of one node per chunk)")
      ->capture_default_str()
      ->check(CLI::Range(std::int64_t{2}, std::int64_t{100000}));
  return [args]() {
    auto format = data::parse_export_format(args->format);
    FrameRange range = parse_frame_range(args->frames);
    data::Dataset ds = open_dataset(args->path, args->allow_unhashed);
    auto files = data::export_sequence(ds, args->sequence, format, range.first, range.last, args->out, args->glb_chunk);
    std::printf("wrote %zu files to %s\n", files.size(), args->out.c_str());
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
