// crosscheck_ours.cpp -- our side of `layers crosscheck`'s timing: the
// stored sequence's scene simulated again (resimulate.h) and timed on one
// thread (see crosscheck.h).
#include "layers/generate/crosscheck.h"
#include "layers/generate/resimulate.h"

namespace layers::generate {

CrosscheckRun resimulate_ours(const std::string& dataset_dir, const std::string& sequence_id, std::int64_t frames) {
  Resimulation again = resimulate(dataset_dir, sequence_id, frames);
  CrosscheckRun run;
  run.label = kOursAgain;
  run.ms_per_frame = again.cpu_ms_per_frame;
  run.garments = std::move(again.garments);
  return run;
}

}  // namespace layers::generate
