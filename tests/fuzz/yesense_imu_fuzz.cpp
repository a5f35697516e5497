// The Yesense IMU codec (drivers/common, yesense_codec.hpp) on any byte stream the IMU's serial
// line can deliver: the frame splitter with any LEN bound, then every checked frame decoded. A
// frame must re-frame to itself; a decoded reading must hold finite values and a unit
// quaternion, and re-encode into a message that decodes to the same reading (the quaternion
// within the protocol's 1e-6 resolution, since decode normalises it).
//
// Input: u8 read size − 1, u8 LEN bound (0: kMaxPayload), then the stream.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "fuzz_check.hpp"
#include "fuzz_input.hpp"
#include "robotd/imu/yesense_codec.hpp"

namespace {

using namespace robotd::imu;
using robotd::fuzz::all_finite;
using robotd::fuzz::FuzzInput;

template <std::size_t N>
bool within(const std::array<double, N>& a, const std::array<double, N>& b, double tolerance) {
  for (std::size_t i = 0; i < N; ++i) {
    if (std::abs(a[i] - b[i]) > tolerance) return false;
  }
  return true;
}

void check_reframes(const yesense::Frame& frame) {
  std::array<std::uint8_t, yesense::kMaxFrame> bytes{};
  const std::size_t size = yesense::encode_frame(frame.sequence, frame.payload, bytes);
  FUZZ_CHECK(size == yesense::kPrefixBytes + frame.payload.size() + yesense::kChecksumBytes);
  yesense::FrameSplitter splitter;
  std::span<const std::uint8_t> rest = std::span(bytes).first(size);
  yesense::Frame again;
  FUZZ_CHECK(splitter.next(rest, again));
  FUZZ_CHECK(again.sequence == frame.sequence && rest.empty());
  FUZZ_CHECK(std::equal(frame.payload.begin(), frame.payload.end(), again.payload.begin(), again.payload.end()));
}

void check_reading(const ImuReading& reading) {
  FUZZ_CHECK(all_finite(reading.orientation_xyzw) && all_finite(reading.angular_velocity_rad_s));
  FUZZ_CHECK(all_finite(reading.linear_acceleration_m_s2) && std::isfinite(reading.temperature_c));
  FUZZ_CHECK(std::isfinite(reading.euler_rad.roll) && std::isfinite(reading.euler_rad.pitch) &&
             std::isfinite(reading.euler_rad.yaw));
  const auto& q = reading.orientation_xyzw;
  FUZZ_CHECK(std::abs(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] - 1.0) < 1e-9);

  std::array<std::uint8_t, yesense::kMaxPayload> payload{};
  const std::size_t size = yesense::encode_payload(reading, payload);
  ImuReading again;
  const auto status = yesense::decode(reading.sequence, std::span(payload).first(size), again);
  FUZZ_CHECK(status == yesense::DecodeStatus::kOk);
  FUZZ_CHECK(again.has_orientation == reading.has_orientation && again.has_euler == reading.has_euler);
  FUZZ_CHECK(again.has_angular_velocity == reading.has_angular_velocity);
  FUZZ_CHECK(again.has_linear_acceleration == reading.has_linear_acceleration);
  FUZZ_CHECK(again.has_temperature == reading.has_temperature && again.has_sample_time == reading.has_sample_time);
  FUZZ_CHECK(again.angular_velocity_rad_s == reading.angular_velocity_rad_s);
  FUZZ_CHECK(again.linear_acceleration_m_s2 == reading.linear_acceleration_m_s2);
  FUZZ_CHECK(again.temperature_c == reading.temperature_c && again.sample_time_us == reading.sample_time_us);
  FUZZ_CHECK(within(again.orientation_xyzw, reading.orientation_xyzw, 2e-6));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput input(data, size);
  const std::uint8_t piece = input.u8();
  const std::size_t bound = input.u8();
  yesense::FrameSplitter splitter(bound == 0 ? yesense::kMaxPayload : bound);
  robotd::fuzz::feed_in_pieces(input.rest(), piece, [&](std::span<const std::uint8_t> bytes) {
    yesense::Frame frame;
    while (splitter.next(bytes, frame)) {
      FUZZ_CHECK(frame.payload.size() <= (bound == 0 ? yesense::kMaxPayload : bound));
      check_reframes(frame);
      ImuReading reading;
      const auto status = yesense::decode(frame.sequence, frame.payload, reading);
      FUZZ_CHECK(yesense::to_string(status) != nullptr);
      if (status == yesense::DecodeStatus::kOk) check_reading(reading);
    }
  });
  return 0;
}
