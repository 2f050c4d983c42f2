// `layers validate`: every schema problem of a dataset, one per line;
// exit 1 if there is any.
#include <cstdio>

#include "layers/data/validate.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_validate(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("validate", "Check a dataset folder or shard file against LAYERS-H5 v1; exit 1 on any problem");
  auto path = std::make_shared<std::string>();
  cmd->add_option("path", *path, "dataset folder or shard .h5 file")->required();
  return [path]() {
    auto problems = data::validate_dataset(*path);
    for (const auto& p : problems) std::printf("%s\n", p.to_string().c_str());
    if (problems.empty()) {
      std::printf("%s: valid LAYERS-H5 (format version 1)\n", path->c_str());
      return static_cast<int>(kOk);
    }
    std::printf("%s: %zu problem%s\n", path->c_str(), problems.size(), problems.size() == 1 ? "" : "s");
    return static_cast<int>(kFailure);
  };
}

}  // namespace layers::app
