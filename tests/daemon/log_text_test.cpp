// Text from the network reaches robotd's log bounded and escaped (app/log_text.hpp).
#include "app/log_text.hpp"

#include <string>

#include <gtest/gtest.h>

namespace robotd::app {
namespace {

TEST(LogText, PrintableTextWithinTheLimitIsShownAsItIs) {
  EXPECT_EQ(log_text("teleop node 7"), "teleop node 7");
  EXPECT_EQ(log_text(""), "");
}

TEST(LogText, LongTextIsCutWithAnEllipsisAndItsLength) {
  const std::string megabyte(1U << 20U, 'n');
  const std::string shown = log_text(megabyte);
  EXPECT_EQ(shown, std::string(kLogTextBytes, 'n') + "…(1048576 bytes)");
  EXPECT_EQ(log_text("abcdef", 3), "abc…(6 bytes)");
}

TEST(LogText, ControlCharactersAndNonAsciiBytesCannotForgeOrGarbleLines) {
  EXPECT_EQ(log_text("a\nb\x1b[0m\t\\"), "a\\x0ab\\x1b[0m\\x09\\\\");
  EXPECT_EQ(log_text("\xc3\xa9\x7f"), "\\xc3\\xa9\\x7f");
}

TEST(LogText, TheLimitCountsInputBytesSoEscapingCannotHideTheCut) {
  EXPECT_EQ(log_text("\n\n\n\n", 2), "\\x0a\\x0a…(4 bytes)");
}

}  // namespace
}  // namespace robotd::app
