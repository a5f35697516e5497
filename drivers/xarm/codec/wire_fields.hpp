// Inside the codec only: the compound fields that requests, replies and reports share (joint
// arrays, poses with millimetre positions) and the size error every parser reports.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "robotd/result.hpp"
#include "xarm_codec.hpp"

namespace robotd::xarm {

inline constexpr double kMmPerM = 1000.0;

/// A register's number on the wire.
constexpr std::uint8_t number(Register reg) { return static_cast<std::uint8_t>(reg); }
inline constexpr std::size_t kF32Bytes = 4;
inline constexpr std::size_t kJointBytes = kMaxDof * kF32Bytes;
inline constexpr std::size_t kPoseBytes = 6 * kF32Bytes;

/// Readers return 0 for values past the end: parsers check the size first, so that never
/// happens, but a mistake would read zeros rather than out of bounds.
double read_f32(ByteReader& reader);
JointValues read_joints(ByteReader& reader);
/// x, y, z mm → m; roll, pitch, yaw rad.
Pose read_pose(ByteReader& reader);

void write_joints(ByteWriter& writer, const JointValues& joints);
/// x, y, z m → mm (scaled before rounding to float); roll, pitch, yaw rad.
void write_pose(ByteWriter& writer, const Pose& pose);

/// "get_err_code reply carries 1 data byte, expected 2" ("at least 2" when longer is accepted).
Error size_error(std::string_view what, std::string_view unit, std::size_t found, std::size_t expected,
                 bool longer_accepted);

}  // namespace robotd::xarm
