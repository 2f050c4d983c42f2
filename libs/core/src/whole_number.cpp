// Plain decimal whole numbers (see whole_number.h).
#include "layers/core/whole_number.h"

namespace layers {

std::optional<long long> parse_whole_number(std::string_view text, long long max) {
  if (text.empty() || max < 0) return std::nullopt;
  long long value = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    const int digit = c - '0';
    if (max - digit < 0 || value > (max - digit) / 10) return std::nullopt;  // value * 10 + digit > max
    value = value * 10 + digit;
  }
  return value;
}

}  // namespace layers
