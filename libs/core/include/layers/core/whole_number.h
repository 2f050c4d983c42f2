// layers/core/whole_number.h -- whole numbers as people and schedulers
// write them in the environment and on the command line (a rank, a port,
// a shard index): decimal digits only, no sign, no spaces, bounded.
#pragma once

#include <optional>
#include <string_view>

namespace layers {

// The value of `text` when it is a plain decimal whole number no larger
// than `max` (>= 0); none otherwise (empty, other characters, too large).
std::optional<long long> parse_whole_number(std::string_view text, long long max);

}  // namespace layers
