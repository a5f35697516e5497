// A session uuid is the session's capability: 128 random bits in the canonical text form.
#include "session/session_uuid.hpp"

#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace robotd::session {
namespace {

TEST(SessionUuid, IsThirtySixCharactersOfLowercaseHexIn8_4_4_4_12Groups) {
  static const std::regex canonical("[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}");
  for (int i = 0; i < 100; ++i) {
    const std::string uuid = random_session_uuid();
    EXPECT_EQ(uuid.size(), 36u);
    EXPECT_TRUE(std::regex_match(uuid, canonical)) << uuid;
  }
}

TEST(SessionUuid, ThousandDrawsAreAllDistinct) {
  std::set<std::string> seen;
  for (int i = 0; i < 1000; ++i) seen.insert(random_session_uuid());
  EXPECT_EQ(seen.size(), 1000u);
}

TEST(SessionUuid, EveryHexDigitPositionVaries) {
  // A constant digit (a formatting slip such as printing one nibble twice) would show here.
  const std::string first = random_session_uuid();
  std::vector<bool> varied(first.size(), false);
  for (int i = 0; i < 200; ++i) {
    const std::string next = random_session_uuid();
    for (std::size_t c = 0; c < first.size(); ++c) varied[c] = varied[c] || next[c] != first[c];
  }
  for (std::size_t c = 0; c < first.size(); ++c) {
    const bool is_dash = c == 8 || c == 13 || c == 18 || c == 23;
    EXPECT_EQ(varied[c], !is_dash) << "position " << c;
  }
}

}  // namespace
}  // namespace robotd::session
