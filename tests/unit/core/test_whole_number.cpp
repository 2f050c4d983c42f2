// parse_whole_number (layers/core/whole_number.h): digits only, bounded,
// no overflow.
#include <gtest/gtest.h>

#include "layers/core/whole_number.h"

namespace layers {
namespace {

TEST(WholeNumber, DigitsUpToTheBoundAndNothingElse) {
  EXPECT_EQ(parse_whole_number("0", 10), 0);
  EXPECT_EQ(parse_whole_number("007", 10), 7);
  EXPECT_EQ(parse_whole_number("65535", 65535), 65535);
  EXPECT_FALSE(parse_whole_number("65536", 65535));
  EXPECT_FALSE(parse_whole_number("2", 1));  // a last digit above the bound
  EXPECT_EQ(parse_whole_number("1", 1), 1);
  for (const char* bad : {"", "-1", "+1", " 1", "1 ", "1.0", "1e3", "0x10", "one"})
    EXPECT_FALSE(parse_whole_number(bad, 1000)) << "'" << bad << "'";
  // Far past the bound (and past long long) is refused, not wrapped.
  EXPECT_FALSE(parse_whole_number("99999999999999999999999", 9223372036854775807LL));
  EXPECT_EQ(parse_whole_number("9223372036854775807", 9223372036854775807LL), 9223372036854775807LL);
}

}  // namespace
}  // namespace layers
