// The running program's folder and the installed layout (see install_paths.h).
#include "layers/core/install_paths.h"

#include <filesystem>
#include <system_error>

namespace layers {

std::string executable_dir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}

std::string installed_dir(const std::string& relative) {
  const std::string exe_dir = executable_dir();
  if (exe_dir.empty()) return "";
  const std::filesystem::path dir = (std::filesystem::path(exe_dir) / ".." / relative).lexically_normal();
  std::error_code ec;
  return std::filesystem::is_directory(dir, ec) ? dir.string() : std::string();
}

}  // namespace layers
