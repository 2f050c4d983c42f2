// apps/layers/frame_range.h -- parsing of "a:b" frame ranges (--frames).
#pragma once

#include <cstdint>
#include <string>

namespace layers::app {

// [first, last); last = -1 means "to the end". "a:b", "a:", ":b", ":" and
// "a" (one frame) are accepted; anything else is an InputError naming
// `flag`.
struct FrameRange {
  std::int64_t first = 0;
  std::int64_t last = -1;
};

FrameRange parse_frame_range(const std::string& text, const std::string& flag = "--frames");

}  // namespace layers::app
