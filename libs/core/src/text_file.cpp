// Whole-file reading (see text_file.h).
#include "layers/core/text_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "layers/core/error.h"

namespace layers {

std::string read_text_file(const std::string& path) {
  // Checked before opening: opening a FIFO for reading waits for a writer.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError(path, "", "a regular file",
                     std::filesystem::is_directory(status) ? "a folder" : "a pipe, socket or device");
  std::ifstream in(path, std::ios::binary);
  if (!in || !std::filesystem::is_regular_file(path))
    throw InputError::message(path, "", "cannot open the file (missing or unreadable)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace layers
