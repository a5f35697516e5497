// The recording format: what the writer writes, the reader reads back, byte for byte where
// docs/recording.md fixes the layout; and what the reader makes of damaged and foreign files.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "recording/little_endian.hpp"
#include "recording/record_codec.hpp"
#include "recording/recording_reader.hpp"
#include "recording/recording_writer.hpp"
#include "recording_test_files.hpp"

namespace robotctl::recording {
namespace {

using testing::TemporaryPath;

constexpr std::int64_t kMs = 1'000'000;

JointStateRecord arm_state(double offset) {
  return JointStateRecord{0, 1'700'000'000'123'456'789, {0.1 + offset, -0.2}, {0.5, 0.0}, {1.25, -3.5}};
}

void write_arm_recording(const std::string& path, int states, bool finish) {
  auto writer = RecordingWriter::create(path, testing::arm_description());
  ASSERT_TRUE(writer) << writer.error().message;
  for (int i = 0; i < states; ++i) {
    testing::append(writer.value(), RecordKind::kJointState, i * kMs, arm_state(i * 0.01));
  }
  if (finish) {
    ASSERT_TRUE(writer.value().finish(states * kMs));
  } else {
    ASSERT_TRUE(writer.value().flush());
  }
}

std::string file_bytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), {});
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file << bytes;
}

TEST(RecordingFormatTest, JointStateRoundTripsThroughItsPayload) {
  const JointStateRecord state = arm_state(0);
  const auto payload = encode(state);
  ASSERT_TRUE(payload);
  // device u16 + stamp i64 + three f64 arrays of 2 values, each with its u16 count.
  EXPECT_EQ(payload->size(), 2U + 8U + 3U * (2U + 2U * 8U));
  EXPECT_EQ(decode_joint_state(*payload), state);
}

TEST(RecordingFormatTest, ControlCommandRoundTripsThroughItsPayload) {
  ControlCommandRecord command = testing::position_command({0, 1}, {0.5F, -0.25F});
  command.stamp_ns = 17;
  command.values.velocities = {1.0F, 2.0F};
  command.values.kp = {100.0F, 100.0F};
  const auto payload = encode(command);
  ASSERT_TRUE(payload);
  EXPECT_EQ(decode_control_command(*payload), command);
}

TEST(RecordingFormatTest, PayloadsAreLittleEndian) {
  const auto payload = encode(JointStateRecord{0x0102, 0x1122334455667788, {1.0}, {}, {}});
  ASSERT_TRUE(payload);
  const std::string expected_start = {'\x02', '\x01', '\x88', '\x77', '\x66', '\x55',
                                      '\x44', '\x33', '\x22', '\x11', '\x01', '\x00'};
  EXPECT_EQ(payload->substr(0, expected_start.size()), expected_start);
  // 1.0 as an IEEE 754 double, least significant byte first.
  EXPECT_EQ(payload->substr(12, 8), std::string("\x00\x00\x00\x00\x00\x00\xf0\x3f", 8));
}

TEST(RecordingFormatTest, APayloadWithBytesMissingOrLeftOverDoesNotDecode) {
  const auto payload = encode(arm_state(0));
  ASSERT_TRUE(payload);
  EXPECT_FALSE(decode_joint_state(payload->substr(0, payload->size() - 1)));
  EXPECT_FALSE(decode_joint_state(*payload + "x"));
  EXPECT_FALSE(decode_control_command(*payload));
}

TEST(RecordingFormatTest, ArraysOverTheFormatsLimitAreNotEncoded) {
  EXPECT_FALSE(encode(JointStateRecord{0, 0, std::vector<double>(70'000), {}, {}}));
}

TEST(RecordingFormatTest, SessionTagIsTheUuidsFirstEightHexDigits) {
  const std::uint32_t tag = session_tag("3f2a9c1e-7b40-4d6e-9c15-a8f2e0b7d341");
  EXPECT_EQ(tag, 0x3f2a9c1eU);
  EXPECT_EQ(session_tag_text(tag), "3f2a9c1e");
  EXPECT_EQ(session_tag_text(0x1), "00000001");
  EXPECT_EQ(session_tag("not-a-uuid"), 0U);
  EXPECT_EQ(session_tag(""), 0U);
}

TEST(RecordingFormatTest, FileStartsWithMagicVersionAndDescription) {
  const TemporaryPath path;
  write_arm_recording(path.str(), 0, true);
  const std::string bytes = file_bytes(path.str());
  ASSERT_GE(bytes.size(), kFileHeaderBytes);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89RBDREC\n"));
  LittleEndianReader header(std::string_view(bytes).substr(8, 8));
  EXPECT_EQ(header.u16(), kMajorVersion);
  EXPECT_EQ(header.u16(), kMinorVersion);
  const std::uint32_t description_bytes = header.u32();
  const auto description = parse_description(std::string_view(bytes).substr(kFileHeaderBytes, description_bytes));
  ASSERT_TRUE(description) << description.error().message;
  EXPECT_EQ(description.value().devices.at(0).joint_names, (std::vector<std::string>{"shoulder", "elbow"}));
  // Then only the end record: kind 255, no payload.
  EXPECT_EQ(bytes.size(), kFileHeaderBytes + description_bytes + kRecordHeaderBytes);
  EXPECT_EQ(static_cast<unsigned char>(bytes[kFileHeaderBytes + description_bytes]), 255U);
}

TEST(RecordingFormatTest, ReaderReturnsTheHeaderAndEveryRecordOfAClosedRecording) {
  const TemporaryPath path;
  write_arm_recording(path.str(), 3, true);
  auto reader = RecordingReader::open(path.str());
  ASSERT_TRUE(reader) << reader.error().message;
  const Description& description = reader.value().description();
  EXPECT_EQ(description.robotd_version, "1.2.3");
  EXPECT_EQ(description.start_time_ns, 1'700'000'000'000'000'000);
  EXPECT_EQ(description.domain_id, 42);
  EXPECT_EQ(description.topics, (std::vector<std::string>{"joint_states", "control_command"}));
  EXPECT_EQ(description.devices.at(0).position_max, (std::vector<double>{1.0, 1.0}));
  for (int i = 0; i < 3; ++i) {
    const auto record = reader.value().next();
    ASSERT_TRUE(record);
    EXPECT_EQ(record->kind, static_cast<std::uint8_t>(RecordKind::kJointState));
    EXPECT_EQ(record->time_ns, i * kMs);
    EXPECT_EQ(decode_joint_state(record->payload), arm_state(i * 0.01));
  }
  const auto end = reader.value().next();
  ASSERT_TRUE(end);
  EXPECT_EQ(end->kind, static_cast<std::uint8_t>(RecordKind::kEnd));
  EXPECT_FALSE(reader.value().next());
  EXPECT_EQ(reader.value().ending(), RecordingReader::Ending::kClosed);
  EXPECT_EQ(reader.value().ending_text(), "");
}

TEST(RecordingFormatTest, TruncatedLastRecordLeavesTheCompleteOnesReadable) {
  const TemporaryPath path;
  write_arm_recording(path.str(), 3, false);
  std::filesystem::resize_file(path.str(), testing::file_size(path.str()) - 5);
  auto reader = RecordingReader::open(path.str());
  ASSERT_TRUE(reader) << reader.error().message;
  int complete = 0;
  while (auto record = reader.value().next()) {
    EXPECT_EQ(decode_joint_state(record->payload), arm_state(complete * 0.01));
    ++complete;
  }
  EXPECT_EQ(complete, 2);
  EXPECT_EQ(reader.value().ending(), RecordingReader::Ending::kTruncated);
  EXPECT_NE(reader.value().ending_text().find("cut short"), std::string::npos) << reader.value().ending_text();
  EXPECT_NE(reader.value().ending_text().find("the 2 records before it are complete"), std::string::npos);
}

TEST(RecordingFormatTest, RecordingCutInsideARecordHeaderIsTruncatedToo) {
  const TemporaryPath path;
  write_arm_recording(path.str(), 2, false);
  std::ofstream(path.str(), std::ios::binary | std::ios::app) << std::string("\x01\x10", 2);
  auto reader = RecordingReader::open(path.str());
  ASSERT_TRUE(reader);
  int complete = 0;
  while (reader.value().next()) ++complete;
  EXPECT_EQ(complete, 2);
  EXPECT_EQ(reader.value().ending(), RecordingReader::Ending::kTruncated);
}

TEST(RecordingFormatTest, RecordingWithoutEndRecordReadsWholeAndSaysItWasNotClosed) {
  const TemporaryPath path;
  write_arm_recording(path.str(), 2, false);
  auto reader = RecordingReader::open(path.str());
  ASSERT_TRUE(reader);
  int complete = 0;
  while (reader.value().next()) ++complete;
  EXPECT_EQ(complete, 2);
  EXPECT_EQ(reader.value().ending(), RecordingReader::Ending::kUnclosed);
  EXPECT_NE(reader.value().ending_text().find("no end record"), std::string::npos);
}

TEST(RecordingFormatTest, RecordKindsOfANewerMinorVersionAreReturnedForTheCallerToSkip) {
  const TemporaryPath path;
  {
    auto writer = RecordingWriter::create(path.str(), testing::arm_description());
    ASSERT_TRUE(writer);
    ASSERT_TRUE(writer.value().append(static_cast<RecordKind>(77), 5, "future"));
    testing::append(writer.value(), RecordKind::kJointState, 6, arm_state(0));
    ASSERT_TRUE(writer.value().finish(7));
  }
  auto reader = RecordingReader::open(path.str());
  ASSERT_TRUE(reader);
  EXPECT_EQ(reader.value().next()->kind, 77);
  EXPECT_EQ(decode_joint_state(reader.value().next()->payload), arm_state(0));
  EXPECT_EQ(kind_name(77), "kind 77");
}

TEST(RecordingFormatTest, OtherMajorVersionIsRefusedNamingBothVersions) {
  const TemporaryPath path;
  write_arm_recording(path.str(), 1, true);
  std::string bytes = file_bytes(path.str());
  bytes[8] = 2;  // major version 2.0
  write_bytes(path.str(), bytes);
  const auto reader = RecordingReader::open(path.str());
  ASSERT_FALSE(reader);
  EXPECT_NE(reader.error().message.find("format version 2.0"), std::string::npos) << reader.error().message;
  EXPECT_NE(reader.error().message.find("reads version 1.x"), std::string::npos) << reader.error().message;
}

TEST(RecordingFormatTest, NewerMinorVersionIsRead) {
  const TemporaryPath path;
  write_arm_recording(path.str(), 1, true);
  std::string bytes = file_bytes(path.str());
  bytes[10] = 9;  // minor version 1.9
  write_bytes(path.str(), bytes);
  const auto reader = RecordingReader::open(path.str());
  ASSERT_TRUE(reader) << reader.error().message;
  EXPECT_EQ(reader.value().minor_version(), 9);
}

TEST(RecordingFormatTest, FileThatIsNotARecordingIsRefusedSayingWhatIsExpected) {
  const TemporaryPath path;
  write_bytes(path.str(), "{\"header\": {\"frame_id\": \"arm\"}}\n");
  const auto reader = RecordingReader::open(path.str());
  ASSERT_FALSE(reader);
  EXPECT_NE(reader.error().message.find("is not a robotd recording"), std::string::npos) << reader.error().message;
  EXPECT_NE(reader.error().message.find("robotctl record"), std::string::npos) << reader.error().message;
}

TEST(RecordingFormatTest, FileCutInsideItsDescriptionIsRefused) {
  const TemporaryPath path;
  write_arm_recording(path.str(), 0, true);
  std::filesystem::resize_file(path.str(), kFileHeaderBytes + 10);
  const auto reader = RecordingReader::open(path.str());
  ASSERT_FALSE(reader);
  EXPECT_NE(reader.error().message.find("ends inside its description"), std::string::npos) << reader.error().message;
}

TEST(RecordingFormatTest, MissingFileIsRefusedWithTheReason) {
  const auto reader = RecordingReader::open("/nonexistent/run.rdrec");
  ASSERT_FALSE(reader);
  EXPECT_NE(reader.error().message.find("/nonexistent/run.rdrec cannot be opened"), std::string::npos);
}

TEST(RecordingFormatTest, WriterSaysWhyItCannotCreateTheFile) {
  const auto writer = RecordingWriter::create("/nonexistent/run.rdrec", testing::arm_description());
  ASSERT_FALSE(writer);
  EXPECT_NE(writer.error().message.find("cannot create /nonexistent/run.rdrec: No such file or directory"),
            std::string::npos)
      << writer.error().message;
}

TEST(RecordingFormatTest, WriterCountsEveryByteItWrites) {
  const TemporaryPath path;
  auto writer = RecordingWriter::create(path.str(), testing::arm_description());
  ASSERT_TRUE(writer);
  testing::append(writer.value(), RecordKind::kJointState, 1, arm_state(0));
  ASSERT_TRUE(writer.value().finish(2));
  EXPECT_EQ(writer.value().bytes(), testing::file_size(path.str()));
}

}  // namespace
}  // namespace robotctl::recording
