// The file names of run and study folders (see run_layout.h).
#include "layers/data/run_layout.h"

namespace layers::data::run_layout {

namespace {
constexpr const char* kEvalPrefix = "eval-";
constexpr const char* kSeedPrefix = "seed-";
}  // namespace

std::string checkpoint(const std::string& which) { return "checkpoint-" + which + ".pt"; }

std::string eval_folder(const std::string& split) { return kEvalPrefix + split; }

bool is_eval_folder(const std::string& name) { return name.rfind(kEvalPrefix, 0) == 0; }

std::string seed_folder(std::uint64_t seed) { return kSeedPrefix + std::to_string(seed); }

bool is_seed_folder(const std::string& name, std::uint64_t* seed) {
  const std::string prefix = kSeedPrefix;
  if (name.size() <= prefix.size() || name.size() > prefix.size() + 19 || name.rfind(prefix, 0) != 0) return false;
  for (std::size_t i = prefix.size(); i < name.size(); ++i)
    if (name[i] < '0' || name[i] > '9') return false;
  if (seed) *seed = std::stoull(name.substr(prefix.size()));
  return true;
}

bool is_result(const std::string& name) {
  return name == checkpoint("last") || name == checkpoint("best") || name == kBench || is_eval_folder(name);
}

}  // namespace layers::data::run_layout
