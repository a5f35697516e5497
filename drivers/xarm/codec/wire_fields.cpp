// The compound fields shared by requests, replies and reports, and the parsers' size error.
#include "wire_fields.hpp"

#include <cstddef>
#include <string>
#include <string_view>

namespace robotd::xarm {

double read_f32(ByteReader& reader) { return reader.f32_le().value_or(0.0); }

JointValues read_joints(ByteReader& reader) {
  JointValues joints{};
  for (double& joint : joints) joint = read_f32(reader);
  return joints;
}

Pose read_pose(ByteReader& reader) {
  Pose pose;
  for (double& axis : pose.position_m) axis = read_f32(reader) / kMmPerM;
  for (double& angle : pose.rpy_rad) angle = read_f32(reader);
  return pose;
}

void write_joints(ByteWriter& writer, const JointValues& joints) {
  for (const double joint : joints) writer.f32_le(joint);
}

void write_pose(ByteWriter& writer, const Pose& pose) {
  for (const double axis : pose.position_m) writer.f32_le(axis * kMmPerM);
  for (const double angle : pose.rpy_rad) writer.f32_le(angle);
}

Error size_error(std::string_view what, std::string_view unit, std::size_t found, std::size_t expected,
                 bool longer_accepted) {
  return make_error(ErrorCode::kInvalidArgument, std::string(what) + " carries " + std::to_string(found) + " " +
                                                     std::string(unit) + (found == 1 ? "" : "s") + ", expected " +
                                                     (longer_accepted ? "at least " : "") + std::to_string(expected));
}

}  // namespace robotd::xarm
