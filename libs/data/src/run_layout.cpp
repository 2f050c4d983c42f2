// The file names of run and study folders (see run_layout.h).
#include "layers/data/run_layout.h"

namespace layers::data::run_layout {

namespace {
constexpr const char* kEvalPrefix = "eval-";
}

std::string checkpoint(const std::string& which) { return "checkpoint-" + which + ".pt"; }

std::string eval_folder(const std::string& split) { return kEvalPrefix + split; }

bool is_eval_folder(const std::string& name) { return name.rfind(kEvalPrefix, 0) == 0; }

bool is_result(const std::string& name) {
  return name == checkpoint("last") || name == checkpoint("best") || name == kBench || is_eval_folder(name);
}

}  // namespace layers::data::run_layout
