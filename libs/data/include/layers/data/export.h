// layers/data/export.h -- exporting a sequence to OBJ or PC2 for Blender
// and other tools.
//
// Meshes are "body" and one per garment (its name, made file-safe;
// "garment<k>" when it has none, suffixed _2, _3, ... while taken:
// mesh_file_names).
//   obj: one file per frame per mesh, <seq>_<mesh>_<frame>.obj (frame
//        zero-padded to 4 digits, absolute frame number); garments keep
//        their UVs.
//   pc2: <seq>_<mesh>.pc2 (startFrame = first exported frame, sampleRate
//        1) plus <seq>_<mesh>.obj, the mesh at the first exported frame,
//        to attach the cache to.
//   glb: <seq>.glb, every mesh and frame in one binary glTF 2.0 file
//        (morph-target frames played by a weights animation, in chunks
//        of `glb_chunk` frames; glb.h).
// Frames are streamed (one at a time); every file is written atomically.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/data/glb.h"

namespace layers::data {

class Dataset;

enum class ExportFormat { Obj, Pc2, Glb };

// The file names (without extension) of a sequence's meshes: "body", then
// one per garment as above; every name distinct and file-safe (letters,
// digits, '-' and '_').
std::vector<std::string> mesh_file_names(const std::vector<std::string>& garment_names);
// "obj", "pc2" or "glb"; InputError naming `source` otherwise.
ExportFormat parse_export_format(const std::string& text, const std::string& source = "--format");

// Exports frames [first, last) of sequence `id` (last < 0: to the end)
// into out_dir (created if missing). Returns the written paths.
std::vector<std::string> export_sequence(const Dataset& dataset, const std::string& id, ExportFormat format,
                                         std::int64_t first, std::int64_t last, const std::string& out_dir,
                                         std::int64_t glb_chunk = kGlbFramesPerChunk);

}  // namespace layers::data
