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

fs::path move_aside(const fs::path& dir, const std::string& field) {
  std::error_code ec;
  const fs::path here = fs::current_path(ec);
  const fs::path target = fs::weakly_canonical(dir, ec);
  if (!here.empty() && !target.empty()) {
    const std::string t = target.string(), h = here.string();
    if (h == t || (h.size() > t.size() && h.compare(0, t.size(), t) == 0 && h[t.size()] == '/'))
      throw InputError(dir.string(), field, "a folder other than the current one or one above it (to move it aside)",
                       "the folder this command runs in");
  }
  const fs::path aside = aside_name(dir);
  fs::rename(dir, aside, ec);
  if (ec)
    throw InputError::message(dir.string(), field, "cannot be moved aside to " + aside.string() + ": " + ec.message());
  return aside;
}

void claim_new_output(const fs::path& out, const std::string& flag, const std::vector<fs::path>& inputs) {
  std::error_code ec;
  const fs::path target = fs::weakly_canonical(out, ec);
  for (const fs::path& input : inputs) {
    const fs::path in = fs::weakly_canonical(input, ec);
    if (in.empty() || target.empty()) continue;
    const std::string t = target.string(), i = in.string();
    if (t == i || (t.size() > i.size() && t.compare(0, i.size(), i) == 0 && t[i.size()] == '/'))
      throw InputError(out.string(), flag, "a path outside the command's inputs (an input is never an output)",
                       t == i ? "the input " + input.string() : "a path inside the input " + input.string());
  }
  if (fs::is_directory(fs::symlink_status(out)) && fs::is_empty(out, ec)) return;  // an empty folder made for it
  if (fs::exists(fs::symlink_status(out)))
    throw InputError(out.string(), flag, "a new path (nothing is overwritten; move or delete it first)",
                     "an existing " + std::string(fs::is_directory(out) ? "folder" : "file"));
}

}  // namespace layers::app
