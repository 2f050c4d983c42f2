// lists.h (private) -- membership and joining of the name lists of a study
// (steps, run names) for checks and log lines.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace layers::study {

inline bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

inline std::string join(const std::vector<std::string>& items, const char* sep = ", ") {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : sep) + s;
  return out;
}

}  // namespace layers::study
