// A session uuid is the session's capability: an RFC 4122 version 4 uuid (122 random bits).
// Its public id is drawn on its own; logs show an unknown uuid only redacted.
#include "session/session_ids.hpp"

#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace robotd::session {
namespace {

TEST(SessionUuid, IsAVersion4UuidInLowercaseHex8_4_4_4_12Groups) {
  // Version nibble 4; variant bits 10, so the fourth group starts with 8, 9, a or b.
  static const std::regex canonical("[0-9a-f]{8}-[0-9a-f]{4}-4[0-9a-f]{3}-[89ab][0-9a-f]{3}-[0-9a-f]{12}");
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
    const bool is_version = c == 14;
    EXPECT_EQ(varied[c], !is_dash && !is_version) << "position " << c;
  }
}

TEST(SessionId, IsEightLowercaseHexDigitsWithEveryPositionVarying) {
  static const std::regex hex8("[0-9a-f]{8}");
  const std::string first = random_session_id();
  std::vector<bool> varied(8, false);
  for (int i = 0; i < 200; ++i) {
    const std::string next = random_session_id();
    ASSERT_TRUE(std::regex_match(next, hex8)) << next;
    for (std::size_t c = 0; c < 8; ++c) varied[c] = varied[c] || next[c] != first[c];
  }
  for (std::size_t c = 0; c < 8; ++c) EXPECT_TRUE(varied[c]) << "position " << c;
}

TEST(SessionId, IsDrawnApartFromTheUuid) {
  // Drawn one after the other, an id that were a slice of the uuid would show up here.
  for (int i = 0; i < 100; ++i) {
    const std::string uuid = random_session_uuid();
    const std::string id = random_session_id();
    EXPECT_EQ(uuid.find(id), std::string::npos) << id << " in " << uuid;
  }
}

TEST(RedactedUuid, ShowsOnlyTheFirstEightCharacters) {
  const std::string uuid = random_session_uuid();
  const std::string shown = redacted_uuid(uuid);
  EXPECT_EQ(shown, uuid.substr(0, 8) + "…");
  EXPECT_EQ(shown.find(uuid.substr(8)), std::string::npos);
}

TEST(RedactedUuid, ShortTextIsShownWhole) {
  EXPECT_EQ(redacted_uuid("uuid-1"), "uuid-1");
  EXPECT_EQ(redacted_uuid(""), "(empty)");
}

TEST(RedactedUuid, CharactersFromTheNetworkCannotForgeLogLines) {
  EXPECT_EQ(redacted_uuid("ab\ncd\x1b[0m-0123456789"), "ab?cd??0…");
}

}  // namespace
}  // namespace robotd::session
