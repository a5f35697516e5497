// The table of arm models: each vendor's published DH table and joint limits, each with its
// public source.
#include <algorithm>
#include <cstddef>
#include <initializer_list>
#include <numbers>

#include "robotd/kinematics/arm_model.hpp"

namespace robotd::kinematics {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMm = 1e-3;
constexpr double kDeg = kPi / 180.0;

/// A table row as the vendor writes it: a and d in mm, α and the θ offset in degrees.
DhLink mm_deg(double a_mm, double alpha_deg, double d_mm, double theta_offset_deg) {
  return DhLink{
      .a_m = a_mm * kMm, .alpha_rad = alpha_deg * kDeg, .d_m = d_mm * kMm, .theta_offset_rad = theta_offset_deg * kDeg};
}

ArmJoints degrees(std::initializer_list<double> values) {
  ArmJoints joints{};
  std::transform(values.begin(), values.end(), joints.begin(), [](double deg) { return deg * kDeg; });
  return joints;
}

ArmModel model(std::string_view name, DhConvention convention, std::initializer_list<DhLink> links,
               EulerConvention euler, std::initializer_list<double> min_deg, std::initializer_list<double> max_deg) {
  ArmModel arm{.name = name, .dof = links.size(), .convention = convention, .euler = euler};
  std::copy(links.begin(), links.end(), arm.links.begin());
  arm.min_rad = degrees(min_deg);
  arm.max_rad = degrees(max_deg);
  return arm;
}

/// `arm` with a tool `length_mm` along its last frame's z axis.
ArmModel with_flange(ArmModel arm, std::string_view name, double length_mm) {
  arm.name = name;
  arm.tool = Eigen::Translation3d(0, 0, length_mm * kMm);
  return arm;
}

// PAROL6: the standard DH table of the PAROL6 commander software (github.com/PCrnjak/
// PAROL-commander-software); link 6 carries the commander's tool, 62.8 mm along the flange axis
// and 45.25 mm across it. Limits: the commander's joint limits (as drivers/parol6/codec/joint_units).
ArmModel parol6() {
  return model("parol6", DhConvention::kStandard,
               {mm_deg(23.42, -90, 110.50, 0), mm_deg(180.00, 180, 0, 0), mm_deg(-43.50, 90, 0, 0),
                mm_deg(0, -90, -176.35, 0), mm_deg(0, 90, 0, 0), mm_deg(-45.25, 180, -62.80, 0)},
               EulerConvention::kParol6Commander, {-123.046875, -145.0088, 107.866, -105.46975, -90, 0},
               {123.046875, -3.375, 287.8675, 105.46975, 90, 360});
}

// PiPER: the modified DH table to the J6 flange of AgileX's piper_sdk (github.com/agilexrobotics/
// piper_sdk, C_PiperForwardKinematics); the firmware's J2/J3 zero offsets are θ2 −172.22°,
// θ3 −102.78° from S-V1.6-3 on (the SDK's dh_is_offset = 1), 2° apart on older firmware
// (dh_is_offset = 0). Limits: the SDK's joint limits (rad there; as drivers/piper/driver/piper_params).
ArmModel piper(std::string_view name, double theta2_deg, double theta3_deg) {
  ArmModel arm = model(name, DhConvention::kModified,
                       {mm_deg(0, 0, 123.0, 0), mm_deg(0, -90, 0, theta2_deg), mm_deg(285.03, 0, 0, theta3_deg),
                        mm_deg(-21.98, 90, 250.75, 0), mm_deg(0, -90, 0, 0), mm_deg(0, 90, 91.0, 0)},
                       EulerConvention::kFixedXyz, {}, {});
  arm.min_rad = {-2.6179, 0.0, -2.967, -1.745, -1.22, -2.09439, 0};
  arm.max_rad = {2.6179, 3.14, 0.0, 1.745, 1.22, 2.09439, 0};
  return arm;
}

// UFACTORY's standard D-H tables ("Kinematic and Dynamic Parameters", xArm-Developer/ufactory_docs)
// and joint ranges (the xArm Python SDK's, as drivers/xarm/codec/models). The xArm 5 and 6 upper arm is 284.5 mm up
// and 53.5 mm forward: a2 = 289.48866 mm at −79.34995°; the xArm 5 forearm and wrist fold into
// a3 = 351.158796 mm (77.5 mm forward, 342.5 mm down).
constexpr double kXarmUpperArmDeg = -1.3849179 / kDeg;

ArmModel xarm5() {
  return model("xarm5", DhConvention::kStandard,
               {mm_deg(0, -90, 267, 0), mm_deg(289.48866, 0, 0, kXarmUpperArmDeg),
                mm_deg(351.158796, 0, 0, 2.7331843 / kDeg), mm_deg(76, -90, 0, -1.3482664 / kDeg), mm_deg(0, 0, 97, 0)},
               EulerConvention::kFixedXyz, {-360, -118, -225, -97, -360}, {360, 120, 11, 180, 360});
}

ArmModel xarm6() {
  return model(
      "xarm6", DhConvention::kStandard,
      {mm_deg(0, -90, 267, 0), mm_deg(289.48866, 0, 0, kXarmUpperArmDeg), mm_deg(77.5, -90, 0, -kXarmUpperArmDeg),
       mm_deg(0, 90, 342.5, 0), mm_deg(76, -90, 0, 0), mm_deg(0, 0, 97, 0)},
      EulerConvention::kFixedXyz, {-360, -118, -225, -360, -97, -360}, {360, 120, 11, 360, 180, 360});
}

ArmModel xarm7() {
  return model("xarm7", DhConvention::kStandard,
               {mm_deg(0, -90, 267, 0), mm_deg(0, 90, 0, 0), mm_deg(52.5, 90, 293, 0), mm_deg(77.5, 90, 0, 0),
                mm_deg(0, 90, 342.5, 0), mm_deg(76, -90, 0, 0), mm_deg(0, 0, 97, 0)},
               EulerConvention::kFixedXyz, {-360, -118, -360, -11, -360, -97, -360},
               {360, 120, 360, 225, 360, 180, 360});
}

ArmModel lite6() {
  return model("lite6", DhConvention::kStandard,
               {mm_deg(0, -90, 243.3, 0), mm_deg(200, 180, 0, -90), mm_deg(87, 90, 0, -90), mm_deg(0, 90, 227.6, 0),
                mm_deg(0, -90, 0, 0), mm_deg(0, 0, 61.5, 0)},
               EulerConvention::kFixedXyz, {-360, -150, -3.5, -360, -124, -360}, {360, 150, 300, 360, 124, 360});
}

ArmModel uf850() {
  return model("uf850", DhConvention::kStandard,
               {mm_deg(0, 90, 364, 0), mm_deg(390, 180, 0, 90), mm_deg(150, -90, 0, 90), mm_deg(0, -90, 426, 0),
                mm_deg(0, 90, 0, 0), mm_deg(0, 0, 90, 0)},
               EulerConvention::kFixedXyz, {-360, -132, -242, -360, -124, -360}, {360, 132, 3.5, 360, 124, 360});
}

// RealMan's modified DH tables (rm_docs, robotParameter pages) to the flange of the standard
// ("-B") version, and the joint ranges of those pages' working-space text (as
// drivers/realman/codec/models). The six-axis force ("-6F") versions have a longer flange: a tool
// along the last axis.
ArmModel rm65() {
  return model("rm65", DhConvention::kModified,
               {mm_deg(0, 0, 240.5, 0), mm_deg(0, 90, 0, 90), mm_deg(256, 0, 0, 90), mm_deg(0, 90, 210, 0),
                mm_deg(0, -90, 0, 0), mm_deg(0, 90, 144, 0)},
               EulerConvention::kFixedXyz, {-178, -130, -135, -178, -128, -360}, {178, 130, 135, 178, 128, 360});
}

ArmModel rm75() {
  return model("rm75", DhConvention::kModified,
               {mm_deg(0, 0, 240.5, 0), mm_deg(0, -90, 0, 0), mm_deg(0, 90, 256, 0), mm_deg(0, -90, 0, 0),
                mm_deg(0, 90, 210, 0), mm_deg(0, -90, 0, 0), mm_deg(0, 90, 144, 0)},
               EulerConvention::kFixedXyz, {-178, -130, -178, -135, -178, -128, -360},
               {178, 130, 178, 135, 178, 128, 360});
}

ArmModel rml63() {
  return model("rml63", DhConvention::kModified,
               {mm_deg(0, 0, 172, 0), mm_deg(-86, -90, 0, -90), mm_deg(380, 0, 0, 90), mm_deg(69, 90, 405, 0),
                mm_deg(0, -90, 0, 180), mm_deg(0, -90, 115, 180)},
               EulerConvention::kFixedXyz, {-178, -178, -178, -178, -178, -360}, {178, 178, 145, 178, 178, 360});
}

ArmModel gen72() {
  return model("gen72", DhConvention::kModified,
               {mm_deg(0, 0, 218, 0), mm_deg(0, -90, 0, 0), mm_deg(0, 90, 280, 0), mm_deg(40, 90, 0, 0),
                mm_deg(-19, -90, 252.5, 0), mm_deg(0, 90, 0, 90), mm_deg(67, 90, 90.5, 0)},
               EulerConvention::kFixedXyz, {-172, -105, -172, -170, -172, -90, -172},
               {172, 105, 172, 55, 172, 120, 172});
}

const std::array<ArmModel, 15>& table() {
  static const std::array<ArmModel, 15> models{
      parol6(),
      piper("piper", -172.22, -102.78),
      piper("piper_plain_dh", -174.22, -100.78),
      xarm5(),
      xarm6(),
      xarm7(),
      lite6(),
      uf850(),
      rm65(),
      with_flange(rm65(), "rm65_6f", 172.5 - 144),
      rm75(),
      with_flange(rm75(), "rm75_6f", 172.5 - 144),
      rml63(),
      with_flange(rml63(), "rml63_6f", 143.5 - 115),
      gen72(),  // its force version's flange is as long (90.5 mm)
  };
  return models;
}

}  // namespace

std::span<const ArmModel> arm_models() { return table(); }

const ArmModel* find_arm_model(std::string_view name) {
  const auto& models = table();
  const auto found =
      std::find_if(models.begin(), models.end(), [name](const ArmModel& arm) { return arm.name == name; });
  return found == models.end() ? nullptr : &*found;
}

}  // namespace robotd::kinematics
