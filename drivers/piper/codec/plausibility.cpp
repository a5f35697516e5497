// The SDK's abnormal-data filter (piper_sdk C_PiperInterface_V2, on by default): feedback
// values no arm can report are dropped, leaving the previous ones. The limits are the SDK's, in
// its wire units (µm, 0.001°); decoded values are compared back in those units.
#include <cmath>
#include <variant>

#include "piper_frames.hpp"
#include "wire_scaling.hpp"

namespace robotd::piper {
namespace {

constexpr double kMaxAxisMicrometres = 1e6;        // 1 m
constexpr double kMaxPoseAngleMilliDeg = 361000;   // 361°
constexpr double kMaxJointMilliDeg = 3000000;      // 3000° (the SDK's comment says 300°; its code says 3000°)
constexpr double kMaxGripperMicrometres = 150000;  // 150 mm

bool within(double value, double scale, double limit) { return std::abs(std::round(value * scale)) <= limit; }
bool length_ok(double m) { return within(m, wire::kMicrometresPerMetre, kMaxAxisMicrometres); }
bool pose_angle_ok(double rad) { return within(rad, wire::kMilliDegPerRad, kMaxPoseAngleMilliDeg); }
bool joint_ok(double rad) { return within(rad, wire::kMilliDegPerRad, kMaxJointMilliDeg); }

bool end_pose_ok(const EndPoseFeedbackPart& part) {
  switch (part.part) {
    case 0:
      return length_ok(part.first) && length_ok(part.second);
    case 1:
      return length_ok(part.first) && pose_angle_ok(part.second);
    default:
      return pose_angle_ok(part.first) && pose_angle_ok(part.second);
  }
}

}  // namespace

bool plausible(const Frame& frame) noexcept {
  if (const auto* pose = std::get_if<EndPoseFeedbackPart>(&frame)) return end_pose_ok(*pose);
  if (const auto* joints = std::get_if<JointFeedbackPair>(&frame)) {
    return joint_ok(joints->first_rad) && joint_ok(joints->second_rad);
  }
  if (const auto* gripper = std::get_if<GripperFeedback>(&frame)) {
    return within(gripper->stroke_m, wire::kMicrometresPerMetre, kMaxGripperMicrometres);
  }
  return true;
}

}  // namespace robotd::piper
