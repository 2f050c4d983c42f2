// layers/core/text_file.h -- reading a whole text file, with the toolkit's
// error for a file that is missing or unreadable.
#pragma once

#include <string>

namespace layers {

// The file's bytes. Throws InputError "<path>: cannot open the file
// (missing or unreadable)" otherwise.
std::string read_text_file(const std::string& path);

}  // namespace layers
