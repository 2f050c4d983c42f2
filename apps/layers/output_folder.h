// output_folder.h -- the one way a verb replaces an output folder it was
// asked to write again: never deleted, moved aside to a free name beside
// it (`train --force`, `report --force`).
#pragma once

#include <filesystem>

namespace layers::app {

// A free name beside `dir`: <dir>.replaced-<UTC time>[-N].
std::filesystem::path aside_name(const std::filesystem::path& dir);

// Renames `dir` to aside_name(dir) and returns the new name. InputError
// (naming `field`) when `dir` is the current folder or a folder above it,
// or the rename fails.
std::filesystem::path move_aside(const std::filesystem::path& dir, const std::string& field);

}  // namespace layers::app
