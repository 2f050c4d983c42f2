// tests/support/file_bytes.h -- a whole file's bytes ("" when unreadable),
// for tests that compare files or mutate them.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

namespace layers::test {

inline std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace layers::test
