// Output folders moved aside (see output_folder.h).
#include "output_folder.h"

#include <ctime>
#include <string>

#include "layers/core/error.h"

namespace layers::app {

namespace fs = std::filesystem;

fs::path aside_name(const fs::path& dir) {
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::gmtime(&now));
  const std::string base = dir.lexically_normal().string();
  const std::string trimmed = (!base.empty() && base.back() == '/') ? base.substr(0, base.size() - 1) : base;
  fs::path candidate = trimmed + ".replaced-" + stamp;
  for (int n = 2; fs::exists(candidate); ++n) candidate = trimmed + ".replaced-" + stamp + "-" + std::to_string(n);
  return candidate;
}

bool same_or_inside(const fs::path& path, const fs::path& folder) {
  std::error_code ec;
  const std::string p = fs::weakly_canonical(path, ec).string();
  if (ec || p.empty()) return false;
  const std::string f = fs::weakly_canonical(folder, ec).string();
  if (ec || f.empty()) return false;
  return p == f || (p.size() > f.size() && p.compare(0, f.size(), f) == 0 && p[f.size()] == '/');
}

fs::path move_aside(const fs::path& dir, const std::string& field) {
  std::error_code ec;
  const fs::path here = fs::current_path(ec);
  if (!here.empty() && same_or_inside(here, dir))
    throw InputError(dir.string(), field, "a folder other than the current one or one above it (to move it aside)",
                     "the folder this command runs in");
  const fs::path aside = aside_name(dir);
  fs::rename(dir, aside, ec);
  if (ec)
    throw InputError::message(dir.string(), field, "cannot be moved aside to " + aside.string() + ": " + ec.message());
  return aside;
}

void claim_new_output(const fs::path& out, const std::string& flag, const std::vector<fs::path>& inputs) {
  std::error_code ec;
  for (const fs::path& input : inputs)
    if (same_or_inside(out, input))
      throw InputError(
          out.string(), flag, "a path outside the command's inputs (an input is never an output)",
          same_or_inside(input, out) ? "the input " + input.string() : "a path inside the input " + input.string());
  if (fs::is_directory(fs::symlink_status(out)) && fs::is_empty(out, ec)) return;  // an empty folder made for it
  if (fs::exists(fs::symlink_status(out)))
    throw InputError(out.string(), flag, "a new path (nothing is overwritten; move or delete it first)",
                     "an existing " + std::string(fs::is_directory(out) ? "folder" : "file"));
}

}  // namespace layers::app
