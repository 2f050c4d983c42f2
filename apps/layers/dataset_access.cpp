// Opening a dataset named on the command line (see dataset_access.h).
#include "dataset_access.h"

#include <spdlog/spdlog.h>

namespace layers::app {

void add_allow_unhashed(CLI::App& cmd, bool& allow) {
  cmd.add_flag("--allow-unhashed", allow,
               "read a dataset written before content hashes, unverified (`layers validate --record-hashes` "
               "records them)");
}

data::Dataset open_dataset(const std::string& path, bool allow_unhashed) {
  data::ReaderOptions options;
  options.allow_unhashed = allow_unhashed;
  if (allow_unhashed)
    spdlog::warn("{}: --allow-unhashed: sequences without a recorded content hash are read unverified", path);
  return data::Dataset::open(path, options);
}

}  // namespace layers::app
