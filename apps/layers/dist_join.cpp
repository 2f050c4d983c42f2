// Joining a data-parallel run from a verb (see dist_join.h).
#include "dist_join.h"

#include <spdlog/spdlog.h>

namespace layers::app {

std::unique_ptr<dist::Group> join_group(const train::ExperimentConfig& config) {
  std::unique_ptr<dist::Group> group =
      dist::join_from_environment(std::chrono::seconds(config.run.dist_timeout_s), config.run.device == "cuda");
  if (group && !group->is_root() && spdlog::get_level() < spdlog::level::warn) spdlog::set_level(spdlog::level::warn);
  return group;
}

}  // namespace layers::app
