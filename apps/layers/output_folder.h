// output_folder.h -- the one way a verb replaces an output folder it was
// asked to write again: never deleted, moved aside to a free name beside
// it (`train --force`, `report --force`); and the one rule for an output
// path a verb writes: new, and none of its inputs.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace layers::app {

// A free name beside `dir`: <dir>.replaced-<UTC time>[-N].
std::filesystem::path aside_name(const std::filesystem::path& dir);

// Renames `dir` to aside_name(dir) and returns the new name. InputError
// (naming `field`) when `dir` is the current folder or a folder above it,
// or the rename fails.
std::filesystem::path move_aside(const std::filesystem::path& dir, const std::string& field);

// Whether `path` is `folder` or lies inside it (both made absolute and
// normal first; false when either cannot be).
bool same_or_inside(const std::filesystem::path& path, const std::filesystem::path& folder);

// An output path (file or folder) a verb is about to write, checked before
// anything is computed or written: InputError naming `flag` when it is one
// of `inputs` or lies inside one of them (an input is never an output),
// or when it exists, other than as an empty folder (nothing a user made
// is overwritten).
void claim_new_output(const std::filesystem::path& out, const std::string& flag,
                      const std::vector<std::filesystem::path>& inputs = {});

}  // namespace layers::app
