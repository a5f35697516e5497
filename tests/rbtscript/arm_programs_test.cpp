// RBTscript on the PiPER, xArm 6 and RealMan RM65 through a real robotd and each vendor's
// simulator: a program per arm (tests/rbtscript/programs/) with every kind of move and the arm's
// gripper ends where its last moves put the tool; and the dry run, on these arms and the PAROL6,
// names the line and column of an unreachable pose, a joint beyond its limit, a straight line
// ending at a singularity and a statement the arm cannot do, without moving the arm.
// The expected poses are worked out here from the programs' numbers with Eigen (the vendors'
// fixed-axis roll, pitch, yaw written out) and compared with the pose the driver reports.
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "parol6_sim_process.hpp"
#include "piper_sim_process.hpp"
#include "pose_tolerances.hpp"
#include "realman_sim_process.hpp"
#include "robotd/rbtscript/device_runner.hpp"
#include "robotd/rbtscript/parser.hpp"
#include "robotd_fixture.hpp"
#include "xarm_sim_process.hpp"

namespace robotd::testing {
namespace {

using rbtscript::RunEnd;

constexpr double kUnmovedRad = 1e-4;  // a dry run sends nothing: the joints stay put

rbtscript::Program parsed(const std::string& text, const std::string& what) {
  rbtscript::ParseResult result = rbtscript::parse_program(text);
  EXPECT_TRUE(result.program.has_value()) << what << ": " << (result.errors.empty() ? "" : result.errors[0].message());
  return result.program.value_or(rbtscript::Program{});
}

rbtscript::Program program_file(const std::string& name) {
  std::ifstream file(std::string(ROBOTD_RBTSCRIPT_PROGRAMS_DIR) + "/" + name);
  std::stringstream text;
  text << file.rdbuf();
  return parsed(text.str(), name);
}

/// A pose as the PiPER, xArm and RealMan write it: mm, and roll a, pitch b, yaw c in degrees
/// about the base's fixed x, y, z axes, R = Rz(c)·Ry(b)·Rx(a).
Eigen::Isometry3d fixed_xyz_pose(double x_mm, double y_mm, double z_mm, double a_deg, double b_deg, double c_deg) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x_mm, y_mm, z_mm) * 1e-3;
  pose.linear() = (Eigen::AngleAxisd(c_deg * kDeg, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(b_deg * kDeg, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(a_deg * kDeg, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  return pose;
}

/// The same in metres and radians, as the drivers' pose ops answer.
Eigen::Isometry3d fixed_xyz_pose_si(double x_m, double y_m, double z_m, double a_rad, double b_rad, double c_rad) {
  return fixed_xyz_pose(x_m * 1e3, y_m * 1e3, z_m * 1e3, a_rad / kDeg, b_rad / kDeg, c_rad / kDeg);
}

/// `pose` moved by (x, y, z mm) along its own axes and turned by `c_deg` about its own z.
Eigen::Isometry3d in_tool_frame(const Eigen::Isometry3d& pose, double x_mm, double y_mm, double z_mm, double c_deg) {
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.translation() = Eigen::Vector3d(x_mm, y_mm, z_mm) * 1e-3;
  delta.linear() = Eigen::AngleAxisd(c_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return pose * delta;
}

void expect_pose(const Eigen::Isometry3d& actual, const Eigen::Isometry3d& expected) {
  EXPECT_LT((actual.translation() - expected.translation()).norm(), kPositionToleranceM)
      << "at " << actual.translation().transpose() * 1e3 << " mm, expected " << expected.translation().transpose() * 1e3
      << " mm";
  const double turn = Eigen::AngleAxisd(expected.linear().transpose() * actual.linear()).angle();
  EXPECT_LT(turn, kAngleToleranceRad) << "orientation off by " << turn / kDeg << "°";
}

/// What a dry run must find on line `line` (column 1), its message naming `problem`.
struct ExpectedProblem {
  std::size_t line;
  std::string problem;
};

/// robotd with one vendor device named after its driver.
class ArmProgramsTest : public RobotdTest {
 protected:
  void start(const std::string& driver, const nlohmann::json& params) {
    device_ = driver;
    start_with_device(vendor_device(driver, params), /*with_sim_arm=*/false);
  }

  rbtscript::DeviceRunReport run(const rbtscript::Program& program, bool dry_run) {
    rbtscript::DeviceRunOptions options;
    options.device = device_;
    options.dry_run = dry_run;
    options.loops = 1;
    auto report = rbtscript::run_on_device(client(), program, options);
    EXPECT_TRUE(report) << report.error().message;
    return report ? std::move(report).value() : rbtscript::DeviceRunReport{};
  }

  /// Runs `program` to its end: no dry-run problems, no failure.
  void run_to_end(const rbtscript::Program& program) {
    const rbtscript::DeviceRunReport report = run(program, /*dry_run=*/false);
    for (const auto& problem : report.problems) ADD_FAILURE() << problem.to_string();
    ASSERT_TRUE(report.outcome.has_value());
    EXPECT_EQ(report.outcome->end, RunEnd::kEnd) << (report.outcome->error ? report.outcome->error->to_string() : "");
  }

  /// The dry run of `text` finds exactly `expected`, in order, and the arm does not move.
  void expect_dry_run_finds(const std::string& text, const std::vector<ExpectedProblem>& expected) {
    const std::vector<double> before = joint_state(device_).position;
    const rbtscript::DeviceRunReport report = run(parsed(text, "dry-run program"), /*dry_run=*/true);
    EXPECT_FALSE(report.outcome.has_value()) << "a dry run ran the program";
    ASSERT_EQ(report.problems.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
      const rbtscript::RunError& found = report.problems[i];
      EXPECT_EQ(found.location.line, expected[i].line) << found.to_string();
      EXPECT_EQ(found.location.column, 1U) << found.to_string();
      EXPECT_NE(found.message.find(expected[i].problem), std::string::npos)
          << "expected '" << expected[i].problem << "' in: " << found.to_string();
    }
    const std::vector<double> after = joint_state(device_).position;
    ASSERT_EQ(after.size(), before.size());
    for (std::size_t j = 0; j < before.size(); ++j) EXPECT_NEAR(after[j], before[j], kUnmovedRad) << "joint " << j + 1;
  }

  /// `read()` comes within `tolerance` of `expected` within a few seconds (a gripper finishes its
  /// move after the program ends): a test failure naming `what` otherwise.
  static void expect_reaches(const std::function<double()>& read, double expected, double tolerance,
                             const std::string& what) {
    double last = read();
    for (int i = 0; i < 250 && std::fabs(last - expected) > tolerance; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      last = read();
    }
    EXPECT_NEAR(last, expected, tolerance) << what;
  }

  std::string device_;
};

// Each dry-run program starts with a joint move to a bent arm (line 1), then: a pose 2 m away
// (line 2), a joint beyond its limit (line 3), a straight line from the bent arm to a pose whose
// only nearby joint solution has the wrist axes lined up (line 4), and an Output the arm has not
// got (line 5). A move that fails leaves the plan where it was, so each is planned from line 1's.
std::vector<ExpectedProblem> dry_run_findings() {
  return {{2, "no joint solution"}, {3, "limit"}, {4, "singularity"}, {5, "cannot do Output"}};
}

class PiperProgramsTest : public ArmProgramsTest {
 protected:
  void SetUp() override { start("piper", {{"can", {{"transport", "standin"}, {"path", sim_.bus_path()}}}}); }
  Eigen::Isometry3d reported_pose() {
    const nlohmann::json flange = call_device("piper", "fk")["flange"];
    return fixed_xyz_pose_si(flange["x_m"].get<double>(), flange["y_m"].get<double>(), flange["z_m"].get<double>(),
                             flange["roll_rad"].get<double>(), flange["pitch_rad"].get<double>(),
                             flange["yaw_rad"].get<double>());
  }
  PiperSimProcess sim_{PiperSimProcess::unique_path("piper-rbt")};
};

TEST_F(PiperProgramsTest, TourEndsAtItsLastLineMovedAlongTheToolZ) {
  run_to_end(program_file("piper_tour.rbt"));
  // MoveCart(230,-40,390,180,50,180) then MoveCartRelTRF(0,0,20,0,0,0).
  expect_pose(reported_pose(), in_tool_frame(fixed_xyz_pose(230, -40, 390, 180, 50, 180), 0, 0, 20, 0));
  // Gripper(200,...): 200/255 of the way from open (the joint's maximum stroke) to closed.
  const DeviceInfo piper = client().list_devices().value().at(0);
  const double open_m = piper.position_max.at(6);
  const double closed_m = piper.position_min.at(6);
  expect_reaches([&] { return call_device("piper", "state")["gripper"]["stroke_m"].get<double>(); },
                 open_m - (open_m - closed_m) * 200.0 / 255.0, 0.002, "the gripper's stroke (m)");
}

TEST_F(PiperProgramsTest, DryRunFindsEachProblemAndMovesNothing) {
  expect_dry_run_finds(
      "MoveJoint(0,60,-60,0,40,0)\n"
      "MovePose(2000,0,300,180,0,180)\n"
      "MoveJoint(0,60,-60,0,90,0)\n"          // J5 is limited to about ±70°
      "MoveCart(230.746,0,438.545,0,85,0)\n"  // J5 at 0: J4 and J6 in line
      "Output(1,HIGH)\n",
      dry_run_findings());
}

class XarmProgramsTest : public ArmProgramsTest {
 protected:
  void SetUp() override {
    start("xarm", {{"model", "xarm6"},
                   {"host", "127.0.0.1"},
                   {"port", sim_.port()},
                   {"report", {{"kind", "real"}, {"port", sim_.report_port()}}}});
  }
  Eigen::Isometry3d reported_pose() {
    const nlohmann::json tcp = call_device("xarm", "get_tcp_pose");
    return fixed_xyz_pose_si(tcp["x_m"].get<double>(), tcp["y_m"].get<double>(), tcp["z_m"].get<double>(),
                             tcp["roll_rad"].get<double>(), tcp["pitch_rad"].get<double>(),
                             tcp["yaw_rad"].get<double>());
  }
  XarmSimProcess sim_{{"--quiet"}};
};

TEST_F(XarmProgramsTest, TourEndsAtItsLastLineMovedAndTurnedAboutTheToolZ) {
  run_to_end(program_file("xarm_tour.rbt"));
  // MoveCart(380,-60,330,180,0,0) then MoveCartRelTRF(0,0,-20,0,0,10).
  expect_pose(reported_pose(), in_tool_frame(fixed_xyz_pose(380, -60, 330, 180, 0, 0), 0, 0, -20, 10));
  // Gripper(255,...): closed, 0 of the xArm gripper's 850 pulses.
  expect_reaches([&] { return call_device("xarm", "gripper_get_position")["position"].get<double>(); }, 0, 10,
                 "the gripper's position (pulses)");
}

TEST_F(XarmProgramsTest, DryRunFindsEachProblemAndMovesNothing) {
  expect_dry_run_finds(
      "MoveJoint(0,-20,-40,0,60,0)\n"
      "MovePose(2000,0,300,180,0,0)\n"
      "MoveJoint(0,-20,30,0,60,0)\n"               // J3 goes no higher than 11°
      "MoveCart(403.166,0,493.21,180,-73.19,0)\n"  // J5 at -13.19°: J4 and J6 in line
      "Output(1,HIGH)\n",
      dry_run_findings());
}

class RealmanProgramsTest : public ArmProgramsTest {
 protected:
  void SetUp() override {
    start("realman", {{"model", "RM65"},
                      {"host", "127.0.0.1"},
                      {"port", sim_.port()},
                      {"push", {{"ip", "127.0.0.1"}, {"port", 0}}}});
  }
  Eigen::Isometry3d reported_pose() {
    const nlohmann::json pose = call_device("realman", "get_current_arm_state")["pose"];
    const nlohmann::json& p = pose["position_m"];
    const nlohmann::json& e = pose["euler_rad"];
    return fixed_xyz_pose_si(p[0].get<double>(), p[1].get<double>(), p[2].get<double>(), e[0].get<double>(),
                             e[1].get<double>(), e[2].get<double>());
  }
  RealmanSimProcess sim_{{"--quiet"}};
};

TEST_F(RealmanProgramsTest, TourEndsAtItsLastLineMovedAlongTheToolZ) {
  run_to_end(program_file("realman_tour.rbt"));
  // MoveCart(-400,-60,280,180,15,0) then MoveCartRelTRF(0,0,20,0,0,0).
  expect_pose(reported_pose(), in_tool_frame(fixed_xyz_pose(-400, -60, 280, 180, 15, 0), 0, 0, 20, 0));
  // Gripper(255,...): closed, the opening 1 of 1..1000.
  expect_reaches([&] { return call_device("realman", "get_gripper_state")["opening"].get<double>(); }, 1, 10,
                 "the gripper's opening");
}

TEST_F(RealmanProgramsTest, DryRunFindsEachProblemAndMovesNothing) {
  expect_dry_run_finds(
      "MoveJoint(0,30,70,0,60,0)\n"
      "MovePose(2000,0,300,180,0,0)\n"
      "MoveJoint(0,30,70,0,150,0)\n"             // J5 is limited to ±128°
      "MoveCart(-476.622,0,400.731,180,80,0)\n"  // J5 at 0: J4 and J6 in line
      "Output(1,HIGH)\n",
      dry_run_findings());
}

class Parol6DryRunTest : public ArmProgramsTest {
 protected:
  void SetUp() override { start("parol6", {{"serial", {{"device", sim_.pty_path()}, {"baud", 3000000}}}}); }
  Parol6SimProcess sim_{Parol6SimProcess::unique_path("parol6-dry"), {"--homed"}};
};

TEST_F(Parol6DryRunTest, DryRunFindsEachProblemAndMovesNothing) {
  // The commander's convention for the pose: MoveCart's end has J5 at 0.
  expect_dry_run_finds(
      "MoveJoint(90,-100,170,0,40,180)\n"
      "MovePose(2000,0,300,-90,0,-90)\n"
      "MoveJoint(90,0,170,0,40,180)\n"  // J2 goes no higher than -3.4°
      "MoveCart(0,231.313,286.015,-90,0,-90)\n"
      "Output(3,HIGH)\n",  // the PAROL6 has OUT1 and OUT2
      dry_run_findings());
}

}  // namespace
}  // namespace robotd::testing
