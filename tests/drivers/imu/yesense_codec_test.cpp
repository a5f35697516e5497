// The Yesense serial output protocol (robotd/imu/yesense_codec.hpp) against the vendor's own
// example frame ("Yesense 通讯协议说明文档" v1.3 §3.2.1) and checksum examples (§3.2.2), round
// trips, damaged input and a fuzz loop.
#include "robotd/imu/yesense_codec.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "robotd/kinematics/rotation.hpp"

namespace robotd::imu::yesense {
namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr double kDeg = std::numbers::pi / 180.0;

/// §3.2.1: TID 0x9240, 88 bytes of acceleration, angular rate, normalised and raw magnetic
/// field, Euler angles and quaternion, then CK1 0x12, CK2 0xF3.
constexpr std::array<std::uint8_t, 95> kVendorFrame = {
    0x59, 0x53, 0x40, 0x92, 0x58, 0x10, 0x0c, 0x3b, 0x21, 0xfe, 0xff, 0x89, 0x2c, 0xfe, 0xff, 0x59, 0x9c, 0x6a, 0xff,
    0x20, 0x0c, 0xd1, 0xa2, 0x02, 0x00, 0xfa, 0xb1, 0x05, 0x00, 0x38, 0xd0, 0x00, 0x00, 0x30, 0x0c, 0x20, 0xff, 0xf1,
    0x07, 0xd0, 0xa0, 0xea, 0xf4, 0xc0, 0x8e, 0xc6, 0xef, 0x31, 0x0c, 0xb4, 0x08, 0x02, 0x00, 0xa2, 0x29, 0xfd, 0xff,
    0xb8, 0xd8, 0xfb, 0xff, 0x40, 0x0c, 0xcb, 0xe4, 0xf4, 0xff, 0xb1, 0xbe, 0x09, 0x00, 0x30, 0x32, 0xb6, 0xf6, 0x41,
    0x10, 0xd4, 0x31, 0x03, 0x00, 0x4d, 0xec, 0xff, 0xff, 0x86, 0xe5, 0xff, 0xff, 0xa9, 0x14, 0xf1, 0xff, 0x12, 0xf3};

/// Acceleration (1, −2.5, 9.80665) m/s², TID 1, worked by hand: 1e6 = 0x000F4240,
/// −2.5e6 = 0xFFD9DA60, 9806650 = 0x0095A33A, little-endian.
constexpr std::array<std::uint8_t, 21> kAccelFrame = {0x59, 0x53, 0x01, 0x00, 0x0E, 0x10, 0x0C, 0x40, 0x42, 0x0F, 0x00,
                                                      0x60, 0xDA, 0xD9, 0xFF, 0x3A, 0xA3, 0x95, 0x00, 0x40, 0xCD};

/// Every frame the splitter finds in `bytes` fed in chunks of `chunk` bytes, copied out.
std::vector<std::pair<std::uint16_t, Bytes>> split(FrameSplitter& splitter, std::span<const std::uint8_t> bytes,
                                                   std::size_t chunk = SIZE_MAX) {
  std::vector<std::pair<std::uint16_t, Bytes>> frames;
  for (std::size_t offset = 0; offset < bytes.size(); offset += chunk) {
    std::span<const std::uint8_t> input(bytes.data() + offset, std::min(chunk, bytes.size() - offset));
    Frame frame;
    while (splitter.next(input, frame))
      frames.emplace_back(frame.sequence, Bytes(frame.payload.begin(), frame.payload.end()));
  }
  return frames;
}

Bytes encoded(const ImuReading& reading) {
  std::array<std::uint8_t, kMaxFrame> out{};
  const std::size_t length = encode(reading, out);
  return {out.begin(), out.begin() + static_cast<std::ptrdiff_t>(length)};
}

Bytes frame_with_payload(std::uint16_t sequence, const Bytes& payload) {
  std::array<std::uint8_t, kMaxFrame> out{};
  const std::size_t length = encode_frame(sequence, payload, out);
  return {out.begin(), out.begin() + static_cast<std::ptrdiff_t>(length)};
}

ImuReading full_reading(std::uint16_t sequence) {
  ImuReading reading;
  reading.sequence = sequence;
  reading.has_orientation = reading.has_angular_velocity = reading.has_linear_acceleration = true;
  reading.has_euler = reading.has_temperature = reading.has_sample_time = true;
  reading.euler_rad = {.roll = 0.3, .pitch = -0.2, .yaw = 1.0};
  reading.orientation_xyzw = kinematics::quaternion_xyzw_from_rpy({0.3, -0.2, 1.0});
  reading.angular_velocity_rad_s = {0.5, -1.25, 3.0};
  reading.linear_acceleration_m_s2 = {-1.5, 2.25, 9.80665};
  reading.temperature_c = 36.57;
  reading.sample_time_us = 4'000'000'000U;
  return reading;
}

Bytes append(Bytes a, std::span<const std::uint8_t> b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(YesenseChecksum, MatchesTheVendorExamples) {
  // §3.2.1: over TID … last payload byte.
  const auto sum = checksum(std::span<const std::uint8_t>(kVendorFrame).subspan(2, kVendorFrame.size() - 4));
  EXPECT_EQ(sum[0], 0x12);
  EXPECT_EQ(sum[1], 0xF3);
  // §3.2.2, the input protocol (same sum): "59 53 03 09 00 05 11 2C" sets 20 Hz output to RAM.
  const Bytes command = {0x03, 0x09, 0x00, 0x05};
  EXPECT_EQ(checksum(command), (std::array<std::uint8_t, 2>{0x11, 0x2C}));
  // "59 53 4d 12 00 02 01 62 ce": AHRS mode to ROM.
  const Bytes mode = {0x4d, 0x12, 0x00, 0x02, 0x01};
  EXPECT_EQ(checksum(mode), (std::array<std::uint8_t, 2>{0x62, 0xCE}));
}

TEST(YesenseCodec, DecodesTheVendorExampleFrame) {
  FrameSplitter splitter;
  const auto frames = split(splitter, kVendorFrame);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].first, 0x9240);
  EXPECT_EQ(frames[0].second.size(), 0x58U);
  ImuReading reading;
  ASSERT_EQ(decode(frames[0].first, frames[0].second, reading), DecodeStatus::kOk);
  EXPECT_EQ(reading.sequence, 0x9240);
  // "0xFFFE213B = −122565 → −0.122565 m/s²" (the document's own reading of the first value).
  ASSERT_TRUE(reading.has_linear_acceleration);
  EXPECT_NEAR(reading.linear_acceleration_m_s2[0], -0.122565, 1e-12);
  EXPECT_NEAR(reading.linear_acceleration_m_s2[1], -0.119671, 1e-12);
  EXPECT_NEAR(reading.linear_acceleration_m_s2[2], -9.790375, 1e-12);
  // "0x0005B1FA = 373242 → 0.373242 deg/s" (y).
  ASSERT_TRUE(reading.has_angular_velocity);
  EXPECT_NEAR(reading.angular_velocity_rad_s[0], 0.172753 * kDeg, 1e-12);
  EXPECT_NEAR(reading.angular_velocity_rad_s[1], 0.373242 * kDeg, 1e-12);
  EXPECT_NEAR(reading.angular_velocity_rad_s[2], 0.053304 * kDeg, 1e-12);
  // Euler items in the order pitch, roll, yaw; "0xF6B63230 → yaw −155.831760 deg".
  ASSERT_TRUE(reading.has_euler);
  EXPECT_NEAR(reading.euler_rad.pitch, -0.727861 * kDeg, 1e-12);
  EXPECT_NEAR(reading.euler_rad.roll, 0.638641 * kDeg, 1e-12);
  EXPECT_NEAR(reading.euler_rad.yaw, -155.831760 * kDeg, 1e-12);
  // q0 … q3 = w, x, y, z; "0xFFF114A9 → −0.977751" (q3), normalised.
  ASSERT_TRUE(reading.has_orientation);
  const double norm = std::sqrt(0.209364 * 0.209364 + 0.005043 * 0.005043 + 0.006778 * 0.006778 + 0.977751 * 0.977751);
  EXPECT_NEAR(reading.orientation_xyzw[0], -0.005043 / norm, 1e-12);
  EXPECT_NEAR(reading.orientation_xyzw[1], -0.006778 / norm, 1e-12);
  EXPECT_NEAR(reading.orientation_xyzw[2], -0.977751 / norm, 1e-12);
  EXPECT_NEAR(reading.orientation_xyzw[3], 0.209364 / norm, 1e-12);
  // The magnetometer items (0x30, 0x31) are skipped; no temperature or timestamp in this frame.
  EXPECT_FALSE(reading.has_temperature);
  EXPECT_FALSE(reading.has_sample_time);
}

TEST(YesenseCodec, VendorEulerAnglesAreZyxOfItsQuaternion) {
  // The convention the decoder assumes, checked on the device's own data: the quaternion's
  // Z-Y-X angles are the frame's Euler item (roll about x, pitch about y), to the device's
  // rounding.
  ImuReading reading;
  FrameSplitter splitter;
  const auto frames = split(splitter, kVendorFrame);
  ASSERT_EQ(frames.size(), 1U);
  ASSERT_EQ(decode(frames[0].first, frames[0].second, reading), DecodeStatus::kOk);
  const auto [x, y, z, w] = reading.orientation_xyzw;
  const double roll = std::atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y));
  const double pitch = std::asin(2 * (w * y - z * x));
  const double yaw = std::atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z));
  EXPECT_NEAR(roll, reading.euler_rad.roll, 0.01 * kDeg);
  EXPECT_NEAR(pitch, reading.euler_rad.pitch, 0.01 * kDeg);
  EXPECT_NEAR(yaw, reading.euler_rad.yaw, 0.01 * kDeg);
}

TEST(YesenseCodec, EncodesAHandWorkedFrame) {
  ImuReading reading;
  reading.sequence = 1;
  reading.has_linear_acceleration = true;
  reading.linear_acceleration_m_s2 = {1.0, -2.5, 9.80665};
  EXPECT_EQ(encoded(reading), Bytes(kAccelFrame.begin(), kAccelFrame.end()));
}

TEST(YesenseCodec, RoundTripsEveryField) {
  const ImuReading sent = full_reading(60'000);
  const Bytes bytes = encoded(sent);
  ASSERT_FALSE(bytes.empty());
  FrameSplitter splitter;
  const auto frames = split(splitter, bytes);
  ASSERT_EQ(frames.size(), 1U);
  ImuReading got;
  ASSERT_EQ(decode(frames[0].first, frames[0].second, got), DecodeStatus::kOk);
  EXPECT_EQ(got.sequence, 60'000);
  ASSERT_TRUE(got.has_orientation && got.has_angular_velocity && got.has_linear_acceleration && got.has_euler &&
              got.has_temperature && got.has_sample_time);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(got.orientation_xyzw[i], sent.orientation_xyzw[i], 2e-6);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(got.angular_velocity_rad_s[i], sent.angular_velocity_rad_s[i], 1e-6 * kDeg);
    EXPECT_NEAR(got.linear_acceleration_m_s2[i], sent.linear_acceleration_m_s2[i], 1e-6);
  }
  EXPECT_NEAR(got.euler_rad.roll, 0.3, 1e-6 * kDeg);
  EXPECT_NEAR(got.euler_rad.pitch, -0.2, 1e-6 * kDeg);
  EXPECT_NEAR(got.euler_rad.yaw, 1.0, 1e-6 * kDeg);
  EXPECT_NEAR(got.temperature_c, 36.57, 1e-9);
  EXPECT_EQ(got.sample_time_us, 4'000'000'000U);
}

TEST(YesenseCodec, EncodingClampsToTheProtocolRange) {
  ImuReading reading;
  reading.has_linear_acceleration = true;
  reading.linear_acceleration_m_s2 = {1e9, -1e9, std::nan("")};
  reading.has_temperature = true;
  reading.temperature_c = 1e6;
  ImuReading got;
  FrameSplitter splitter;
  const auto frames = split(splitter, encoded(reading));
  ASSERT_EQ(frames.size(), 1U);
  ASSERT_EQ(decode(frames[0].first, frames[0].second, got), DecodeStatus::kOk);
  EXPECT_NEAR(got.linear_acceleration_m_s2[0], 2147.483647, 1e-9);
  EXPECT_NEAR(got.linear_acceleration_m_s2[1], -2147.483648, 1e-9);
  EXPECT_EQ(got.linear_acceleration_m_s2[2], 0.0);
  EXPECT_NEAR(got.temperature_c, 327.67, 1e-9);
}

TEST(YesenseCodec, EncodeRefusesAShortBuffer) {
  std::array<std::uint8_t, 20> small{};
  ImuReading reading = full_reading(1);
  EXPECT_EQ(encode(reading, small), 0U);
  EXPECT_EQ(encode(ImuReading{}, std::span<std::uint8_t>(small)), 0U);  // nothing to send
  std::array<std::uint8_t, kMaxFrame + 10> big{};
  const std::array<std::uint8_t, kMaxPayload + 1> too_long{};
  EXPECT_EQ(encode_frame(1, too_long, big), 0U);
}

TEST(YesenseCodec, EulerOnlyGivesTheOrientation) {
  ImuReading reading;
  reading.has_euler = true;
  reading.euler_rad = {.roll = 0.1, .pitch = 0.2, .yaw = -0.3};
  ImuReading got;
  FrameSplitter splitter;
  const auto frames = split(splitter, encoded(reading));
  ASSERT_EQ(frames.size(), 1U);
  ASSERT_EQ(decode(frames[0].first, frames[0].second, got), DecodeStatus::kOk);
  ASSERT_TRUE(got.has_orientation);
  const auto expected = kinematics::quaternion_xyzw_from_rpy({0.1, 0.2, -0.3});
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(got.orientation_xyzw[i], expected[i], 1e-7);
}

TEST(YesenseCodec, RejectsMalformedItems) {
  ImuReading reading;
  // An item whose LEN runs past the message.
  EXPECT_EQ(decode(1, Bytes{0x10, 0x0C, 0x00, 0x00}, reading), DecodeStatus::kTruncatedItem);
  // A lone byte where an item header should be.
  EXPECT_EQ(decode(1, Bytes{0x01, 0x02, 0x10, 0x00, 0x99}, reading), DecodeStatus::kTruncatedItem);
  // A known item with the wrong length.
  EXPECT_EQ(decode(1, Bytes{0x10, 0x04, 0x00, 0x00, 0x00, 0x00}, reading), DecodeStatus::kBadItemLength);
  // A zero quaternion.
  Bytes zero_quaternion = {0x41, 0x10};
  zero_quaternion.resize(18, 0x00);
  EXPECT_EQ(decode(1, zero_quaternion, reading), DecodeStatus::kBadQuaternion);
  // Items it does not read are skipped by their length, whatever it is.
  EXPECT_EQ(decode(1, Bytes{0x99, 0x03, 0x01, 0x02, 0x03, 0x01, 0x02, 0x90, 0x0E}, reading), DecodeStatus::kOk);
  EXPECT_TRUE(reading.has_temperature);
  EXPECT_NEAR(reading.temperature_c, 37.28, 1e-9);
  // An empty message is a frame with nothing in it.
  EXPECT_EQ(decode(7, Bytes{}, reading), DecodeStatus::kOk);
  EXPECT_EQ(reading.sequence, 7);
  EXPECT_FALSE(reading.has_orientation);
}

TEST(YesenseSplitter, CountsAChecksumErrorAndKeepsGoing) {
  Bytes damaged(kAccelFrame.begin(), kAccelFrame.end());
  damaged[8] ^= 0x01U;
  FrameSplitter splitter;
  const auto frames = split(splitter, append(append(damaged, kAccelFrame), kVendorFrame));
  ASSERT_EQ(frames.size(), 2U);
  EXPECT_EQ(frames[0].first, 1);
  EXPECT_EQ(frames[1].first, 0x9240);
  EXPECT_EQ(splitter.counters().checksum_errors, 1U);
  EXPECT_EQ(splitter.counters().frames, 2U);
  // A damaged CK2 alone is also caught.
  Bytes bad_ck2(kAccelFrame.begin(), kAccelFrame.end());
  bad_ck2.back() ^= 0x80U;
  EXPECT_TRUE(split(splitter, bad_ck2).empty());
  EXPECT_EQ(splitter.counters().checksum_errors, 2U);
}

TEST(YesenseSplitter, ResyncsAfterGarbageAndFalseHeaders) {
  // Noise, then a false header claiming a 255-byte message that swallows the real frames
  // after it: its checksum fails and the search resumes inside it.
  Bytes stream = {0x00, 0x59, 0x00, 0x53, 0x59, 0x59, 0x53, 0x12, 0x34, 0xFF, 0x01, 0x02};
  for (std::uint16_t sequence = 1; sequence <= 5; ++sequence) stream = append(stream, encoded(full_reading(sequence)));
  stream = append(stream, Bytes(300, 0xAA));
  FrameSplitter splitter;
  const auto frames = split(splitter, stream);
  ASSERT_EQ(frames.size(), 5U);
  for (std::uint16_t i = 0; i < 5; ++i) EXPECT_EQ(frames[i].first, i + 1);
  EXPECT_EQ(splitter.counters().checksum_errors, 1U);
  EXPECT_GT(splitter.counters().bytes_discarded, 300U);
}

TEST(YesenseSplitter, AnyChunkingGivesTheSameFrames) {
  Bytes stream;
  for (std::uint16_t sequence = 1; sequence <= 20; ++sequence) stream = append(stream, encoded(full_reading(sequence)));
  for (const std::size_t chunk : {std::size_t{1}, std::size_t{2}, std::size_t{7}, std::size_t{64}, SIZE_MAX}) {
    FrameSplitter splitter;
    const auto frames = split(splitter, stream, chunk);
    ASSERT_EQ(frames.size(), 20U) << "chunk " << chunk;
    for (std::uint16_t i = 0; i < 20; ++i) EXPECT_EQ(frames[i].first, i + 1);
  }
}

TEST(YesenseSplitter, WaitsForTheRestOfATruncatedFrame) {
  FrameSplitter splitter;
  const Bytes first(kVendorFrame.begin(), kVendorFrame.begin() + 40);
  const Bytes rest(kVendorFrame.begin() + 40, kVendorFrame.end());
  EXPECT_TRUE(split(splitter, first).empty());
  EXPECT_EQ(split(splitter, rest).size(), 1U);
  // reset() drops a partial frame: its tail alone is not a frame.
  EXPECT_TRUE(split(splitter, first).empty());
  splitter.reset();
  EXPECT_TRUE(split(splitter, rest).empty());
  EXPECT_EQ(splitter.counters().frames, 1U);
}

TEST(YesenseSplitter, BoundsTheMessageLength) {
  FrameSplitter splitter(64);
  Bytes stream = frame_with_payload(3, Bytes(100, 0x00));  // unknown items' bytes: LEN 100 > 64
  stream = append(stream, kAccelFrame);
  const auto frames = split(splitter, stream);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].first, 1);
  EXPECT_EQ(splitter.counters().oversize, 1U);
}

TEST(YesenseSplitter, FuzzedBytesNeverYieldABadFrame) {
  std::mt19937 random(12345);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<std::size_t> chunk(1, 300);
  std::uniform_int_distribution<int> noise_length(0, 40);
  FrameSplitter splitter;
  std::uint16_t sent = 0;
  std::vector<std::uint16_t> received;
  for (int round = 0; round < 2000; ++round) {
    // Noise rich in header bytes, then a real frame.
    Bytes stream(static_cast<std::size_t>(noise_length(random)));
    for (auto& value : stream) {
      const int draw = byte(random);
      value = draw < 40 ? kHeader1 : draw < 80 ? kHeader2 : static_cast<std::uint8_t>(draw);
    }
    stream = append(stream, encoded(full_reading(++sent)));
    std::size_t offset = 0;
    while (offset < stream.size()) {
      const std::size_t take = std::min(chunk(random), stream.size() - offset);
      std::span<const std::uint8_t> input(stream.data() + offset, take);
      offset += take;
      Frame frame;
      while (splitter.next(input, frame)) {
        ImuReading reading;
        (void)decode(frame.sequence, frame.payload, reading);  // whatever a false frame holds
        received.push_back(frame.sequence);
      }
    }
  }
  // A false header near the end may claim a message longer than what followed: the frames
  // after it wait for the bytes that settle its checksum.
  const Bytes tail(kMaxFrame, 0x00);
  std::span<const std::uint8_t> input(tail);
  Frame frame;
  while (splitter.next(input, frame)) received.push_back(frame.sequence);
  // Each real frame came out exactly once, in order (noise of ≤ 40 bytes cannot hide a frame
  // whose header follows it: a false header's checksum fails and the search resumes).
  std::vector<std::uint16_t> real;
  for (const std::uint16_t sequence : received) {
    if (sequence >= 1 && sequence <= sent && (real.empty() || sequence == real.back() + 1)) real.push_back(sequence);
  }
  EXPECT_EQ(real.size(), sent);
  EXPECT_EQ(splitter.counters().frames, received.size());
}

TEST(YesenseSplitter, RandomBytesDecodeWithoutHarm) {
  std::mt19937 random(777);
  std::uniform_int_distribution<int> byte(0, 255);
  FrameSplitter splitter;
  Bytes stream(1 << 20);
  for (auto& value : stream) value = static_cast<std::uint8_t>(byte(random));
  std::span<const std::uint8_t> input(stream);
  Frame frame;
  std::size_t frames = 0;
  while (splitter.next(input, frame)) {
    ++frames;
    ImuReading reading;
    (void)decode(frame.sequence, frame.payload, reading);  // any status; never out of bounds (ASan)
  }
  EXPECT_EQ(splitter.counters().frames, frames);
  EXPECT_GT(splitter.counters().bytes_discarded, stream.size() / 2);
  // Random payloads of random length decode to a status, never past their end.
  for (int round = 0; round < 20'000; ++round) {
    Bytes payload(static_cast<std::size_t>(byte(random)));
    for (auto& value : payload) value = static_cast<std::uint8_t>(byte(random) < 64 ? 0x10 : byte(random));
    ImuReading reading;
    const DecodeStatus status = decode(1, payload, reading);
    EXPECT_NE(to_string(status), nullptr);
  }
}

}  // namespace
}  // namespace robotd::imu::yesense
