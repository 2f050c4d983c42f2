// Frame range parsing (see frame_range.h).
#include "frame_range.h"

#include <cctype>

#include "layers/core/error.h"

namespace layers::app {
namespace {
bool parse_count(const std::string& s, std::int64_t& out) {
  if (s.empty() || s.size() > 12) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  out = std::stoll(s);
  return true;
}
}  // namespace

FrameRange parse_frame_range(const std::string& text, const std::string& flag) {
  const std::string expected = "a frame range a:b (first frame a, up to but excluding b), a:, :b or a";
  FrameRange range;
  auto colon = text.find(':');
  if (colon == std::string::npos) {
    if (!parse_count(text, range.first)) throw InputError(flag, "", expected, "'" + text + "'");
    range.last = range.first + 1;
    return range;
  }
  std::string a = text.substr(0, colon), b = text.substr(colon + 1);
  if ((!a.empty() && !parse_count(a, range.first)) || (!b.empty() && !parse_count(b, range.last)))
    throw InputError(flag, "", expected, "'" + text + "'");
  if (range.last >= 0 && range.last <= range.first)
    throw InputError(flag, "", "an end frame after the first frame", "'" + text + "'");
  return range;
}

}  // namespace layers::app
