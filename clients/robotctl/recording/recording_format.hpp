// The robotd recording format (docs/recording.md): what the file header holds and what kinds of
// records follow it. Every number is little-endian with a fixed width.
//
//   file header   magic (8 bytes), major version (u16), minor version (u16),
//                 description length (u32), description (UTF-8 JSON)
//   records       kind (u8), payload length (u32), receive time in ns since the start (i64), payload
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "robotd/messages.hpp"
#include "robotd/result.hpp"

namespace robotctl::recording {

/// 0x89 and '\n' catch a file mangled as text, as in PNG's signature.
inline constexpr std::array<char, 8> kMagic = {'\x89', 'R', 'B', 'D', 'R', 'E', 'C', '\n'};
/// A reader reads every file of its major version; a newer minor version only adds record kinds,
/// which older readers skip.
inline constexpr std::uint16_t kMajorVersion = 1;
inline constexpr std::uint16_t kMinorVersion = 0;
inline constexpr std::size_t kFileHeaderBytes = 16;
inline constexpr std::size_t kRecordHeaderBytes = 13;
/// Larger lengths are taken for corruption, not allocated.
inline constexpr std::uint32_t kLargestDescriptionBytes = 16U << 20U;
inline constexpr std::uint32_t kLargestPayloadBytes = 16U << 20U;

enum class RecordKind : std::uint8_t {
  kJointState = 1,      // binary, record_codec.hpp
  kControlCommand = 2,  // binary, record_codec.hpp
  kSessionStatus = 3,   // JSON (sessions named by their public ids)
  kDeviceStatus = 4,    // JSON
  kEnd = 255,           // no payload; the recording was closed, not cut off
};

/// "joint_state", "control_command", ... or "kind N" for a kind this reader does not know.
std::string kind_name(std::uint8_t kind);

/// The topics a recording can hold, by ROS name without the '/'.
const std::vector<std::string>& recordable_topics();

/// A device as /list_devices described it when the recording began. Records name devices by
/// their index in Description::devices.
struct RecordedDevice {
  std::string name;
  std::string driver;
  std::string model;
  double rate_hz = 0;
  std::vector<std::string> joint_names;
  std::vector<double> position_min;      // rad
  std::vector<double> position_max;      // rad
  std::vector<double> velocity_max;      // rad/s
  std::vector<double> acceleration_max;  // rad/s²
  std::vector<double> effort_max;        // N·m
};

RecordedDevice recorded_device(const robotd::DeviceInfo& device);

/// The file header's JSON description.
struct Description {
  std::string robotd_version;      // of the robotctl that recorded
  std::int64_t start_time_ns = 0;  // CLOCK_REALTIME when recording began
  std::int32_t domain_id = 0;
  std::vector<std::string> topics;
  std::vector<RecordedDevice> devices;
};

/// "2024-05-01T12:34:56Z" for a CLOCK_REALTIME time in ns.
std::string utc_time_text(std::int64_t time_ns);

/// The whole file header: magic, version, description length and description.
std::string encode_file_header(const Description& description);
/// The description from its JSON text; the error says which field is missing or wrong.
robotd::Result<Description> parse_description(std::string_view json_text);

}  // namespace robotctl::recording
