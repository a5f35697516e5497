// The PAROL6 commander docs' example programs, unmodified, on robotd-parol6-sim through a real
// robotd: each ends where the commander's rules put the arm. The expected poses are worked out
// here from the scripts' own numbers with Eigen (the commander's angle convention written out),
// and compared with the driver's forward kinematics of the measured joints.
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "parol6_sim_process.hpp"
#include "pose_tolerances.hpp"
#include "robotd/rbtscript/device_runner.hpp"
#include "robotd/rbtscript/parser.hpp"
#include "robotd_fixture.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;
using rbtscript::RunEnd;

rbtscript::Program example(const std::string& name) {
  std::ifstream file(std::string(ROBOTD_RBTSCRIPT_EXAMPLES_DIR) + "/" + name);
  std::stringstream text;
  text << file.rdbuf();
  rbtscript::ParseResult parsed = rbtscript::parse_program(text.str());
  EXPECT_TRUE(parsed.program.has_value()) << name << ": " << (parsed.errors.empty() ? "" : parsed.errors[0].message());
  return parsed.program.value_or(rbtscript::Program{});
}

/// A pose as the commander writes it: mm, and Rx, Ry, Rz in degrees turned into
/// R = Rx(Rz)·Ry(Ry)·Rz(Rx) (spatialmath's SE3.RPY(..., order="xyz"): the first angle about z).
Eigen::Isometry3d commander_pose(double x_mm, double y_mm, double z_mm, double rx_deg, double ry_deg, double rz_deg) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x_mm, y_mm, z_mm) * 1e-3;
  pose.linear() = (Eigen::AngleAxisd(rz_deg * kDeg, Eigen::Vector3d::UnitX()) *
                   Eigen::AngleAxisd(ry_deg * kDeg, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(rx_deg * kDeg, Eigen::Vector3d::UnitZ()))
                      .toRotationMatrix();
  return pose;
}

class Parol6ProgramsTest : public RobotdTest {
 protected:
  void SetUp() override {
    // The board's silence and robotd's feedback timeout widened from 50 and 100 ms: a run is a
    // minute of streaming, and a simulator starved that long on a loaded machine (or under the
    // sanitizers) would end it with a lost link, which is not what these tests are about.
    const nlohmann::json params{{"serial", {{"device", sim_.pty_path()}, {"baud", 3000000}}},
                                {"reply_timeout_ms", 250}};
    nlohmann::json device = vendor_device("parol6", params);
    device["feedback_timeout_ms"] = 400;
    start_with_device(device, /*with_sim_arm=*/false);
  }

  /// One pass of `program` on the PAROL6; the run's outcome.
  rbtscript::RunOutcome run_once(const rbtscript::Program& program,
                                 std::function<void(const rbtscript::Progress&)> on_statement = {}) {
    rbtscript::DeviceRunOptions options;
    options.device = "parol6";
    options.loops = 1;
    options.on_statement = std::move(on_statement);
    auto report = rbtscript::run_on_device(client(), program, options);
    EXPECT_TRUE(report) << report.error().message;
    if (!report) return {};
    for (const auto& problem : report.value().problems) ADD_FAILURE() << problem.to_string();
    EXPECT_TRUE(report.value().outcome.has_value());
    const rbtscript::RunOutcome outcome = report.value().outcome.value_or(rbtscript::RunOutcome{});
    if (outcome.error) ADD_FAILURE() << outcome.error->to_string();
    return outcome;
  }

  /// The tool pose the driver computes from `joints_rad` (the measured joints when empty).
  Eigen::Isometry3d tool_pose(const std::vector<double>& joints_rad = {}) {
    const nlohmann::json fk =
        joints_rad.empty() ? call_device("parol6", "fk") : call_device("parol6", "fk", {{"joints_rad", joints_rad}});
    const nlohmann::json& tool = fk["tool"];
    return commander_pose(tool["x_m"].get<double>() * 1e3, tool["y_m"].get<double>() * 1e3,
                          tool["z_m"].get<double>() * 1e3, tool["roll_rad"].get<double>() / kDeg,
                          tool["pitch_rad"].get<double>() / kDeg, tool["yaw_rad"].get<double>() / kDeg);
  }

  void expect_joints_deg(const std::vector<double>& expected_deg) {
    const JointState state = joint_state("parol6");
    ASSERT_EQ(state.position.size(), expected_deg.size());
    for (std::size_t j = 0; j < expected_deg.size(); ++j) {
      EXPECT_NEAR(state.position[j], expected_deg[j] * kDeg, kAngleToleranceRad) << "joint " << j + 1;
    }
  }

  static void expect_pose(const Eigen::Isometry3d& actual, const Eigen::Isometry3d& expected) {
    EXPECT_LT((actual.translation() - expected.translation()).norm(), kPositionToleranceM)
        << "at " << actual.translation().transpose() * 1e3 << " mm, expected "
        << expected.translation().transpose() * 1e3 << " mm";
    const double turn = Eigen::AngleAxisd(expected.linear().transpose() * actual.linear()).angle();
    EXPECT_LT(turn, kAngleToleranceRad) << "orientation off by " << turn / kDeg << "°";
  }

  Parol6SimProcess sim_{Parol6SimProcess::unique_path("parol6-rbt"), {"--homed"}};
};

TEST_F(Parol6ProgramsTest, SimpleJointSpaceLoopEndsAtItsLastMoveJoint) {
  const rbtscript::RunOutcome outcome = run_once(example("joint_space_loop"));
  EXPECT_EQ(outcome.end, RunEnd::kLoopLimit);
  expect_joints_deg({66.129, -117.368, 136.77, 46.28, -29.588, 149.293});
}

TEST_F(Parol6ProgramsTest, CartesianTrfExampleEndsAtItsLastMoveCartPose) {
  const rbtscript::RunOutcome outcome = run_once(example("cartesian_trf"));
  EXPECT_EQ(outcome.end, RunEnd::kEnd);
  expect_pose(tool_pose(), commander_pose(82.89, 191.698, 162.369, -40.587, 26.026, -107.028));
}

TEST_F(Parol6ProgramsTest, RelativeTrfMovesTheToolAlongItsOwnX) {
  const rbtscript::RunOutcome outcome = run_once(example("cartesian_relative_trf"));
  EXPECT_EQ(outcome.end, RunEnd::kEnd);
  // MoveJoint(90.0,-90.0,180.001,0.0,0.0,180.0) then MoveCartRelTRF(-80,0,0,0,0,0): the tool
  // 80 mm back along its own x axis, turned no further.
  const Eigen::Isometry3d start = tool_pose({90.0 * kDeg, -90.0 * kDeg, 180.001 * kDeg, 0.0, 0.0, 180.0 * kDeg});
  Eigen::Isometry3d expected = start;
  expected.translation() += start.linear().col(0) * -0.080;
  expect_pose(tool_pose(), expected);
}

TEST_F(Parol6ProgramsTest, Ssg48GripperProgramGripsMovesAndEndsAtItsMoveCartPose) {
  const rbtscript::RunOutcome outcome = run_once(example("ssg48_gripper"));
  EXPECT_EQ(outcome.end, RunEnd::kEnd);
  expect_pose(tool_pose(), commander_pose(4.317, 103.384, 192.319, -84.465, 1.447, -143.154));
  const nlohmann::json gripper = call_device("parol6", "gripper_state");
  EXPECT_NEAR(gripper["position"].get<int>(), 100, 2) << gripper.dump();
}

TEST_F(Parol6ProgramsTest, OutputClickSetsOut1HighThenLow) {
  // After each Delay(1) (before the statement that follows it): OUT1 as the board reports it
  // a second after the Output before the delay.
  std::vector<bool> out1_after_delays;
  std::string_view previous;
  const rbtscript::RunOutcome outcome = run_once(example("output_click"), [&](const rbtscript::Progress& at) {
    if (previous.starts_with("Delay")) out1_after_delays.push_back(call_device("parol6", "io")["out1"].get<bool>());
    previous = at.text;
  });
  EXPECT_EQ(outcome.end, RunEnd::kLoopLimit);
  EXPECT_EQ(out1_after_delays, (std::vector<bool>{true, false}));
  EXPECT_EQ(outcome.statements_run, 6U);  // Begin, Output, Delay, Output, Delay, Loop
  const nlohmann::json io = call_device("parol6", "io");
  EXPECT_FALSE(io["out1"].get<bool>()) << io.dump();
}

}  // namespace
}  // namespace robotd::testing
