// file_names.h -- how import tells files apart by name (import's own):
// a path's extension in lower case (".obj", ".pc2", ".glb").
#pragma once

#include <cctype>
#include <filesystem>
#include <string>

namespace layers::import {

inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace layers::import
