// Forward kinematics: the SDK's C_PiperForwardKinematics.CalFK link poses against robotd's, for
// both DH variants (dh_is_offset 0 and 1).
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "conformance_report.hpp"
#include "kinematics/piper_kinematics.hpp"
#include "vector_file.hpp"

namespace robotd::piper::conformance {
namespace {

using nlohmann::json;
using robotd::conformance::load_json_lines;
using robotd::conformance::Outcome;
using robotd::conformance::record;

// The SDK computes in mm and degrees with Python floats, robotd in m and rad with Eigen: the
// same formulas, so both agree to rounding; 1e-6 mm and 1e-6° leave room for it.
constexpr double kPositionToleranceMm = 1e-6;
constexpr double kAngleToleranceDeg = 1e-6;
constexpr double kDegPerRad = 180.0 / M_PI;

/// Angles compared on the circle: −180° and 180° are the same.
double angle_gap_deg(double a, double b) {
  const double gap = std::fmod(std::abs(a - b), 360.0);
  return std::min(gap, 360.0 - gap);
}

/// The largest departure of robotd's pose from the SDK's [x, y, z mm, rx, ry, rz deg], or an
/// empty string when within tolerance.
std::string departure(const json& sdk, const CartesianPose& pose) {
  const std::array<double, 3> position_mm{pose.x_m * 1e3, pose.y_m * 1e3, pose.z_m * 1e3};
  const std::array<double, 3> angles_deg{pose.rx_rad * kDegPerRad, pose.ry_rad * kDegPerRad, pose.rz_rad * kDegPerRad};
  for (std::size_t i = 0; i < 3; ++i) {
    if (std::abs(sdk.at(i).get<double>() - position_mm[i]) > kPositionToleranceMm ||
        angle_gap_deg(sdk.at(i + 3).get<double>(), angles_deg[i]) > kAngleToleranceDeg) {
      return "SDK " + sdk.dump() + " robotd [" + std::to_string(position_mm[0]) + ", " +
             std::to_string(position_mm[1]) + ", " + std::to_string(position_mm[2]) + ", " +
             std::to_string(angles_deg[0]) + ", " + std::to_string(angles_deg[1]) + ", " +
             std::to_string(angles_deg[2]) + "]";
    }
  }
  return {};
}

TEST(FkReplay, LinkPosesAgreeWithTheSdk) {
  const std::vector<json> vectors = load_json_lines("fk.jsonl");
  ASSERT_FALSE(vectors.empty());
  for (const json& vector : vectors) {
    const auto q = vector.at("joints_rad").get<std::array<double, kArmJoints>>();
    const DhVariant variant = vector.at("dh_is_offset").get<int>() == 1 ? DhVariant::kOffset : DhVariant::kPlain;
    const json& links = vector.at("links");
    ASSERT_EQ(links.size(), std::size_t{kArmJoints});
    const std::array<CartesianPose, kArmJoints> poses = link_poses(q, variant);
    for (std::size_t link = 0; link < poses.size(); ++link) {
      const std::string gap = departure(links.at(link), poses[link]);
      EXPECT_TRUE(gap.empty()) << "link " << link + 1 << ", joints " << vector.at("joints_rad").dump()
                               << ", dh_is_offset " << vector.at("dh_is_offset") << ": " << gap;
      record("fk", gap.empty() ? Outcome::passed : Outcome::failed);
    }
    const std::string flange = departure(links.back(), forward_kinematics(q, variant));
    EXPECT_TRUE(flange.empty()) << "forward_kinematics, joints " << vector.at("joints_rad").dump() << ": " << flange;
  }
}

}  // namespace
}  // namespace robotd::piper::conformance
