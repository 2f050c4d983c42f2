// layers/train/scene_tensors.h -- LAYERS-H5 data (layers/data) as the
// tensors the model interface takes (layers/zoo/model.h): a sequence's
// static data, a window of frames, and the StepInput of one frame of it.
// Garments can be restricted to the inner layer (inner-only experiments).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <ATen/ATen.h>

#include "layers/data/sequence.h"
#include "layers/zoo/model.h"

namespace layers::train {

// Which garments of a sequence a run uses.
struct GarmentSelection {
  bool inner_only = false;
  // Indices into the sequence's garments (data order).
  std::vector<std::size_t> pick(const std::vector<data::GarmentStatic>& garments) const;
};

// Static data; `id` becomes zoo::SequenceStatic::id (cache key).
zoo::SequenceStatic to_model_static(const data::SequenceStatic& s, const GarmentSelection& selection);

// A window's per-frame arrays, frame axis first (n frames).
struct FrameTensors {
  std::int64_t first_frame = 0;      // absolute frame of row 0
  at::Tensor body;                   // [n,Vb,3]
  at::Tensor root, root_rot;         // [n,3], [n,4]
  at::Tensor joints;                 // [n,J,3,4] (undefined when the data has none)
  at::Tensor wind_rotation;          // [n,4]
  at::Tensor wind_strength;          // [n]
  std::vector<at::Tensor> garments;  // selected garments, [n,V,3] each

  std::int64_t frames() const { return body.size(0); }
};

FrameTensors to_frame_tensors(const data::Window& window, const std::vector<data::GarmentStatic>& garments,
                              const GarmentSelection& selection);

// The StepInput predicting row i+1 from rows i-1 and i (1 <= i < frames-1)
// with the given garment states at i-1 and i.
zoo::StepInput step_input(const FrameTensors& frames, std::int64_t i, std::vector<zoo::GarmentState> states);
// The ground-truth garment states at rows i-1 and i.
std::vector<zoo::GarmentState> true_states(const FrameTensors& frames, std::int64_t i);
// Every tensor moved to `device`.
FrameTensors to_device(const FrameTensors& frames, const at::Device& device);

}  // namespace layers::train
