// layers/generate/resimulate.h -- a stored scene of a dataset made by
// `layers generate` simulated again from the generator config its
// dataset.yaml records, optionally at a finer garment resolution, and
// timed frame by frame on the calling thread. Used by `layers crosscheck`
// (our solver beside Blender) and `layers bench --simulator` (our solver
// beside a learned model at the same garment size).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace layers::generate {

struct ResimulateOptions {
  // Multiplies the fit's edge length (0.5: about 4x garment vertices, as
  // one midpoint subdivision); the result must stay within the fit's
  // allowed range.
  double edge_scale = 1.0;
  bool keep_positions = true;  // keep every recorded frame's garment positions
};

struct Resimulation {
  double cpu_ms_per_frame = 0;   // CPU time of this thread, recorded frames 1..n-1
  double wall_ms_per_frame = 0;  // wall clock over the same frames
  std::int64_t garment_vertices = 0;
  std::vector<std::vector<float>> garments;  // per garment, frames x vertices x 3 (keep_positions)
};

// Sequence `sequence_id` (seq-NNNNNN) of the dataset folder `dataset_dir`:
// drape and blend untimed, then frames 0..frames-1 recorded. With
// edge_scale 1 the positions equal the stored ones while the solver is
// unchanged. InputError (one line) when the manifest or its generator
// config is missing, the id is not one the generator made, frames is
// outside 2..the recorded count, the scaled edge length is out of range,
// or the scene cannot be made.
Resimulation resimulate(const std::string& dataset_dir, const std::string& sequence_id, std::int64_t frames,
                        const ResimulateOptions& options = {});

// The same checks without simulating (everything but the sequence id):
// what `layers bench --simulator` runs before timing anything, at its
// finest level's edge scale.
void check_resimulation(const std::string& dataset_dir, std::int64_t frames, double edge_scale);

}  // namespace layers::generate
