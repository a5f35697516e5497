#include "sim_params.hpp"

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace robotd::sim {
namespace {

using nlohmann::json;

json full_arm_params() {
  return json::parse(R"({
    "model": "robotd simulated 6-joint arm",
    "joint_defaults": {"effort_max_nm": 30, "default_kp": 80, "external_torque_nm": -1.5},
    "joints": [
      {"name": "base", "position_min_rad": -2.6, "position_max_rad": 2.6},
      {"name": "shoulder", "inertia_kg_m2": 0.2, "external_torque_nm": -4},
      {"name": "elbow", "initial_position_rad": 0.5},
      {"name": "wrist_1"},
      {"name": "wrist_2", "kd_max": 10, "default_kd": 2},
      {"name": "wrist_3", "damping_nm_s_rad": 0}
    ],
    "imu": true
  })");
}

std::string error_of(const json& params) {
  const Result<SimParams> parsed = parse_sim_params(params);
  if (parsed.ok()) return "(parsed without error)";
  EXPECT_EQ(parsed.error().code, ErrorCode::kInvalidArgument);
  return parsed.error().message;
}

TEST(SimParams, AcceptsArmWithNamedJointsAndAppliesJointDefaults) {
  const Result<SimParams> parsed = parse_sim_params(full_arm_params());
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const SimParams& params = parsed.value();
  EXPECT_EQ(params.model, "robotd simulated 6-joint arm");
  EXPECT_TRUE(params.imu);
  ASSERT_EQ(params.joints.size(), 6u);
  EXPECT_EQ(params.joints[0].name, "base");
  EXPECT_DOUBLE_EQ(params.joints[0].limits.position_min_rad, -2.6);
  EXPECT_DOUBLE_EQ(params.joints[0].limits.effort_max_nm, 30);
  EXPECT_DOUBLE_EQ(params.joints[0].default_kp, 80);
  EXPECT_DOUBLE_EQ(params.joints[0].external_torque_nm, -1.5);
  EXPECT_DOUBLE_EQ(params.joints[1].inertia_kg_m2, 0.2);
  EXPECT_DOUBLE_EQ(params.joints[1].external_torque_nm, -4);
  EXPECT_DOUBLE_EQ(params.joints[2].initial_position_rad, 0.5);
  EXPECT_DOUBLE_EQ(params.joints[4].limits.kd_max, 10);
  EXPECT_DOUBLE_EQ(params.joints[4].default_kd, 2);
  EXPECT_DOUBLE_EQ(params.joints[5].damping_nm_s_rad, 0);
}

TEST(SimParams, JointCountNamesJointsWithBuiltInDefaults) {
  const Result<SimParams> parsed = parse_sim_params(json{{"joint_count", 23}});
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const SimParams& params = parsed.value();
  EXPECT_EQ(params.model, "robotd sim");
  EXPECT_FALSE(params.imu);
  ASSERT_EQ(params.joints.size(), 23u);
  EXPECT_EQ(params.joints[0].name, "joint1");
  EXPECT_EQ(params.joints[22].name, "joint23");
  const SimJointParams& joint = params.joints[7];
  EXPECT_DOUBLE_EQ(joint.limits.position_min_rad, -3.0);
  EXPECT_DOUBLE_EQ(joint.limits.position_max_rad, 3.0);
  EXPECT_DOUBLE_EQ(joint.limits.velocity_max_rad_s, 3.0);
  EXPECT_DOUBLE_EQ(joint.limits.acceleration_max_rad_s2, 10.0);
  EXPECT_DOUBLE_EQ(joint.limits.effort_max_nm, 50.0);
  EXPECT_DOUBLE_EQ(joint.limits.kp_max, 500.0);
  EXPECT_DOUBLE_EQ(joint.limits.kd_max, 50.0);
  EXPECT_DOUBLE_EQ(joint.default_kp, 100.0);
  EXPECT_DOUBLE_EQ(joint.default_kd, 5.0);
  EXPECT_DOUBLE_EQ(joint.inertia_kg_m2, 0.05);
  EXPECT_DOUBLE_EQ(joint.damping_nm_s_rad, 0.5);
  EXPECT_DOUBLE_EQ(joint.external_torque_nm, 0);
  EXPECT_DOUBLE_EQ(joint.initial_position_rad, 0);
}

TEST(SimParams, RejectsBothJointCountAndJoints) {
  json params = full_arm_params();
  params["joint_count"] = 6;
  EXPECT_EQ(error_of(params), "joint_count: give either joint_count or joints, not both");
}

TEST(SimParams, RejectsNeitherJointCountNorJoints) {
  const std::string error = error_of(json{{"model", "x"}});
  EXPECT_NE(error.find("joints: missing"), std::string::npos) << error;
  EXPECT_NE(error.find("joint_count"), std::string::npos) << error;
}

TEST(SimParams, RejectsJointCountOutsideOneToMaxJoints) {
  EXPECT_EQ(error_of(json{{"joint_count", 0}}), "joint_count: expected an integer in 1..64, got 0");
  EXPECT_EQ(error_of(json{{"joint_count", 65}}), "joint_count: expected an integer in 1..64, got 65");
  EXPECT_EQ(error_of(json{{"joints", json::array()}}), "joints: expected 1..64 joints, got 0");
}

TEST(SimParams, RejectsUnknownKeyNamingItsPath) {
  json params = full_arm_params();
  params["joints"][1]["intertia_kg_m2"] = 0.1;
  const std::string error = error_of(params);
  EXPECT_EQ(error.rfind("joints[1].intertia_kg_m2: unknown key", 0), 0u) << error;

  params = full_arm_params();
  params["imu_rate_hz"] = 100;
  EXPECT_EQ(error_of(params).rfind("imu_rate_hz: unknown key", 0), 0u);
}

TEST(SimParams, RejectsWrongTypeNamingItsPath) {
  json params = full_arm_params();
  params["joints"][0]["kp_max"] = "high";
  EXPECT_EQ(error_of(params), R"(joints[0].kp_max: expected a number, got "high")");
}

TEST(SimParams, RejectsNonPositiveInertia) {
  json params = full_arm_params();
  params["joints"][2]["inertia_kg_m2"] = -1;
  EXPECT_EQ(error_of(params), "joints[2].inertia_kg_m2: expected a number > 0, got -1");
}

TEST(SimParams, RejectsPositionMinNotBelowMax) {
  json params = full_arm_params();
  params["joints"][2]["position_min_rad"] = 3.0;
  EXPECT_EQ(error_of(params), "joints[2].position_min_rad: expected less than position_max_rad (3), got 3");
}

TEST(SimParams, RejectsDefaultGainsAboveTheirMaxima) {
  json params = full_arm_params();
  params["joints"][3]["default_kp"] = 600;
  params["joints"][4]["default_kd"] = 11;
  EXPECT_EQ(error_of(params),
            "joints[3].default_kp: expected at most kp_max (500), got 600; "
            "joints[4].default_kd: expected at most kd_max (10), got 11");
}

TEST(SimParams, RejectsInitialPositionOutsideLimits) {
  json params = full_arm_params();
  params["joints"][0]["initial_position_rad"] = 2.7;
  EXPECT_EQ(error_of(params),
            "joints[0].initial_position_rad: expected within position_min_rad..position_max_rad (-2.6..2.6), got 2.7");
}

TEST(SimParams, RejectsDuplicateAndMalformedJointNames) {
  json params = full_arm_params();
  params["joints"][3]["name"] = "elbow";
  params["joints"][4]["name"] = "wrist 2";
  params["joints"][5].erase("name");
  EXPECT_EQ(error_of(params), R"(joints[3].name: "elbow" is already the name of joints[2]; )"
                              R"(joints[4].name: expected a non-empty name of letters, digits and _, got "wrist 2"; )"
                              R"(joints[5].name: missing; expected a joint name of letters, digits and _)");
}

TEST(SimParams, ReportsAProblemInheritedFromJointDefaultsOnceAtJointDefaults) {
  json params = full_arm_params();
  params["joint_defaults"]["default_kp"] = 900;
  EXPECT_EQ(error_of(params), "joint_defaults.default_kp: expected at most kp_max (500), got 900");
}

TEST(SimParams, EveryErrorNamesTheKeyPathThatCausedIt) {
  const struct {
    const char* params;
    std::string path;
  } cases[] = {
      {R"({"joint_count": 2, "model": 7})", "model: "},
      {R"({"joint_count": 2, "imu": "yes"})", "imu: "},
      {R"({"joint_count": "six"})", "joint_count: "},
      {R"({"joint_count": 2, "joint_defaults": 1})", "joint_defaults: "},
      {R"({"joint_count": 2, "joint_defaults": {"velocity_max_rad_s": 0}})", "joint_defaults.velocity_max_rad_s: "},
      {R"({"joint_count": 2, "joint_defaults": {"damping_nm_s_rad": -0.1}})", "joint_defaults.damping_nm_s_rad: "},
      {R"({"joints": [{"name": "a"}, 5]})", "joints[1]: "},
      {R"({"joints": [{"name": "a", "effort_max_nm": 0}]})", "joints[0].effort_max_nm: "},
      {R"({"joints": [{"name": "a", "default_kd": -1}]})", "joints[0].default_kd: "},
      {R"({"joints": [{"name": "a", "position_max_rad": -4}]})", "joints[0].position_min_rad: "},
      {R"({"joints": [{"name": 3}]})", "joints[0].name: "},
      {R"({"joints": "all"})", "joints: "},
  };
  for (const auto& test_case : cases) {
    const std::string error = error_of(json::parse(test_case.params));
    EXPECT_EQ(error.rfind(test_case.path, 0), 0u) << test_case.params << " gave: " << error;
  }
}

}  // namespace
}  // namespace robotd::sim
