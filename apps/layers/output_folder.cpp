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

}  // namespace layers::app
