// Opening an experiment's dataset and model (see session.h).
#include "layers/train/session.h"

#include <ATen/Context.h>
#include <spdlog/spdlog.h>

#include <filesystem>

#include "layers/core/error.h"
#include "layers/data/stats.h"
#include "layers/train/compute_threads.h"
#include "layers/zoo/model_config.h"

namespace layers::train {

Session open_session(const ExperimentConfig& config, const zoo::Registry& registry, int device_index,
                     const std::string& dataset) {
  if (config.data.dataset.empty())
    throw InputError(config.source, "data.dataset", "a dataset folder (made by `layers generate`)", "nothing");
  {
    std::error_code ec;
    if (!std::filesystem::exists(config.data.dataset, ec))
      throw InputError(config.source, "data.dataset", "a dataset folder (made by `layers generate`) or shard file",
                       "'" + config.data.dataset + "' (no such folder or file)");
  }
  if (config.run.device == "cuda" && !at::hasCUDA())
    throw InputError(config.source, "run.device", "a device this build can use (cpu)", "cuda, but torch has no CUDA");
  set_compute_threads(config.run.threads);
  at::manual_seed(config.run.seed);
  data::ReaderOptions reader;
  reader.allow_unhashed = config.data.allow_unhashed;
  if (reader.allow_unhashed)
    spdlog::warn("{}: data.allow_unhashed: sequences without a recorded content hash are read unverified",
                 config.data.dataset);
  Session s{config, data::Dataset::open(dataset.empty() ? config.data.dataset : dataset, reader), nullptr,
            GarmentSelection{config.data.inner_only},
            config.run.device == "cuda" && device_index >= 0
                ? at::Device(at::kCUDA, static_cast<c10::DeviceIndex>(device_index))
                : at::Device(config.run.device == "cuda" ? at::kCUDA : at::kCPU)};
  s.model = zoo::create_model(registry, config.model, "model");
  s.model->to(s.device);
  const std::string stats = (std::filesystem::path(config.data.dataset) / "stats.h5").string();
  if (!std::filesystem::exists(stats))
    throw InputError(config.data.dataset, "stats.h5", "the training statistics (layers generate / layers stats)",
                     "no such file");
  s.model->set_normalization(zoo::Normalization::from_stats(data::read_stats(stats)));
  return s;
}

SequenceRollout sequence_truth(Session& s, const std::string& id, std::int64_t horizon) {
  SequenceRollout r;
  r.id = id;
  const std::int64_t n = s.dataset.info(id).n_frames;
  if (n < 3) throw InputError(s.dataset.path(), "sequence '" + id + "'", "at least 3 frames", std::to_string(n));
  const std::int64_t count = horizon <= 0 ? n : std::min(n, horizon + 2);
  auto statics = s.dataset.statics(id);
  r.statics = std::make_shared<const zoo::SequenceStatic>(to_model_static(*statics, s.selection));
  r.frames = to_frame_tensors(s.dataset.read_frames(id, 0, count), statics->garments, s.selection);
  return r;
}

SequenceRollout rollout_sequence(Session& s, const std::string& id, std::int64_t horizon, double diverge_mm,
                                 bool keep_predictions, bool rates) {
  SequenceRollout r = sequence_truth(s, id, horizon);
  s.model->prepare(*r.statics);
  RolloutOptions options;
  options.start = 1;
  options.steps = r.frames.frames() - 2;
  options.diverge_mm = diverge_mm;
  options.keep_predictions = keep_predictions;
  options.rates = rates;
  r.result = rollout(*s.model, s.model->sequence(), to_device(r.frames, s.device), options);
  return r;
}

}  // namespace layers::train
