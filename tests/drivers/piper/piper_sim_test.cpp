// robotd-piper-sim as a driver sees it: a real process on the stand-in CAN bus, spoken to with
// the codec through a real stand-in connection, and steered through its control channel.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "codec/piper_frames.hpp"
#include "kinematics/piper_kinematics.hpp"
#include "piper_sim_process.hpp"
#include "robotd/transport/can_transport.hpp"

namespace robotd::piper {
namespace {

using namespace std::chrono_literals;
using testing::PiperSimProcess;
using transport::CanIo;
using transport::CanLinkConfig;
using Clock = std::chrono::steady_clock;
using Joints = std::array<double, kArmJoints>;

constexpr double kWireRad = 2e-5;  // 0.001° on the wire, rounded
constexpr std::uint8_t kEnabledBit = 0x40;

/// What the test's bus node has heard from the arm.
struct Heard {
  ArmStatus status;
  bool status_seen = false;
  Joints joints{};
  std::uint8_t joint_pairs = 0;  // bit per 0x2A5–0x2A7 frame
  CartesianPose pose;
  GripperFeedback gripper;
  bool gripper_seen = false;
  std::array<HighSpeedInfo, kArmJoints> high{};
  std::array<LowSpeedInfo, kArmJoints> low{};
  std::uint8_t low_seen = 0;   // bit per joint
  std::vector<Frame> replies;  // 0x473, 0x476, 0x478, 0x47B, 0x47C, 0x47E
  std::string firmware;        // 0x4AF text
  int firmware_frames = 0;
  int frames = 0;
  int undecodable = 0;

  bool all_enabled() const {
    return low_seen == 0x3F && std::all_of(low.begin(), low.end(), [](const LowSpeedInfo& info) {
             return (info.status_bits & kEnabledBit) != 0;
           });
  }
  bool none_enabled() const {
    return low_seen == 0x3F && std::none_of(low.begin(), low.end(), [](const LowSpeedInfo& info) {
             return (info.status_bits & kEnabledBit) != 0;
           });
  }
  template <class T>
  std::vector<T> replies_of() const {
    std::vector<T> out;
    for (const Frame& frame : replies) {
      if (const T* reply = std::get_if<T>(&frame)) out.push_back(*reply);
    }
    return out;
  }
};

CanLinkConfig standin(const std::string& path) {
  CanLinkConfig config;
  config.kind = CanLinkConfig::Kind::kStandIn;
  config.path = path;
  return config;
}

/// Runs the simulator with `arguments` to its end; its exit status (stdout to /dev/null).
int run_to_exit(const std::vector<std::string>& arguments) {
  return testing::run_to_exit(PiperSimProcess::executable(), arguments);
}

class PiperSimTest : public ::testing::Test {
 protected:
  void SetUp() override { start({"--quiet"}); }

  void start(const std::vector<std::string>& arguments) {
    link_.reset();
    sim_ = std::make_unique<PiperSimProcess>("", arguments);
    connect();
  }

  void connect() {
    link_ = transport::make_can_transport(standin(sim_->bus_path()));
    auto opened = link_->open();
    ASSERT_TRUE(opened) << opened.error().message;
    heard_ = Heard{};
  }

  template <class T>
  void send(const T& frame) {
    send_message(encode(frame));
  }
  void send_message(const CanMessage& message) { ASSERT_EQ(link_->send(message), CanIo::kDone); }
  void send_joint_targets(const Joints& targets) {
    for (const CanMessage& message : encode_joint_targets(targets)) send_message(message);
  }
  void send_pose(const CartesianPose& pose) {
    for (const CanMessage& message : encode_end_pose_target(pose)) send_message(message);
  }
  void enable_all() {
    send(MotorEnable{.motor = kAllJoints, .enable = true});
    ASSERT_TRUE(wait_for([this] { return heard_.all_enabled(); }, 1s)) << "the joints never reported enabled";
  }
  void mode(MoveMode move_mode, std::uint8_t speed_percent, bool mit = false) {
    send(ModeControl{.ctrl_mode = ControlMode::kCanCommand,
                     .move_mode = move_mode,
                     .speed_percent = speed_percent,
                     .mit = mit,
                     .residence_time_s = 0,
                     .installation = 0});
  }

  /// Takes every waiting frame off the link into `heard_`; kClosed once the link is gone.
  CanIo drain() {
    CanMessage message;
    while (true) {
      const CanIo result = link_->receive(message);
      if (result == CanIo::kNone || result == CanIo::kClosed) return result;
      if (result == CanIo::kDone) note(message);
    }
  }

  /// Drains until `done()` holds or `timeout` passes.
  bool wait_for(const std::function<bool()>& done, std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline) {
      if (drain() == CanIo::kClosed) return false;
      if (done()) return true;
      std::this_thread::sleep_for(1ms);
    }
    return false;
  }

  void listen_for(std::chrono::milliseconds duration) {
    wait_for([] { return false; }, duration);
  }

  /// Waits until the joints report `targets` and rest there.
  bool wait_until_at(const Joints& targets, std::chrono::milliseconds timeout, double tolerance = 1e-3) {
    return wait_for(
        [&] {
          for (std::size_t i = 0; i < targets.size(); ++i) {
            if (std::abs(heard_.joints[i] - targets[i]) > tolerance || heard_.high[i].speed_rad_s != 0) return false;
          }
          return heard_.joint_pairs == 0x07;
        },
        timeout);
  }

  void note(const CanMessage& message) {
    ++heard_.frames;
    if (message.id == can_id::kFirmware && !message.extended) {
      ++heard_.firmware_frames;
      heard_.firmware.append(message.data.begin(), message.data.begin() + message.length);
      return;
    }
    const std::optional<Frame> frame = decode(message);
    if (!frame) {
      ++heard_.undecodable;
      return;
    }
    if (const auto* status = std::get_if<ArmStatus>(&*frame)) {
      heard_.status = *status;
      heard_.status_seen = true;
    } else if (const auto* pair = std::get_if<JointFeedbackPair>(&*frame)) {
      const auto index = static_cast<std::size_t>(pair->pair) * 2;
      heard_.joints.at(index) = pair->first_rad;
      heard_.joints.at(index + 1) = pair->second_rad;
      heard_.joint_pairs = static_cast<std::uint8_t>(heard_.joint_pairs | (1U << pair->pair));
    } else if (const auto* part = std::get_if<EndPoseFeedbackPart>(&*frame)) {
      if (part->part == 0) {
        heard_.pose.x_m = part->first;
        heard_.pose.y_m = part->second;
      } else if (part->part == 1) {
        heard_.pose.z_m = part->first;
        heard_.pose.rx_rad = part->second;
      } else {
        heard_.pose.ry_rad = part->first;
        heard_.pose.rz_rad = part->second;
      }
    } else if (const auto* gripper = std::get_if<GripperFeedback>(&*frame)) {
      heard_.gripper = *gripper;
      heard_.gripper_seen = true;
    } else if (const auto* high = std::get_if<HighSpeedInfo>(&*frame)) {
      heard_.high.at(static_cast<std::size_t>(high->joint - 1)) = *high;
    } else if (const auto* low = std::get_if<LowSpeedInfo>(&*frame)) {
      heard_.low.at(static_cast<std::size_t>(low->joint - 1)) = *low;
      heard_.low_seen = static_cast<std::uint8_t>(heard_.low_seen | (1U << (low->joint - 1)));
    } else {
      heard_.replies.push_back(*frame);
    }
  }

  nlohmann::json state() { return sim_->control({{"op", "state"}}); }

  std::unique_ptr<PiperSimProcess> sim_;
  std::unique_ptr<transport::CanTransport> link_;
  Heard heard_;
};

// --- feedback ---------------------------------------------------------------------------------

TEST_F(PiperSimTest, FeedbackArrivesAtAbout3040FramesPerSecond) {
  listen_for(100ms);
  heard_ = Heard{};
  listen_for(1000ms);
  EXPECT_GE(heard_.frames, 2000);
  EXPECT_LE(heard_.frames, 4000);
  EXPECT_EQ(heard_.undecodable, 0);
  EXPECT_TRUE(heard_.status_seen);
  EXPECT_EQ(heard_.joint_pairs, 0x07);
  EXPECT_TRUE(heard_.gripper_seen);
  EXPECT_EQ(heard_.low_seen, 0x3F);
}

class PiperSimInitialTest : public PiperSimTest {
 protected:
  void SetUp() override {}
};

TEST_F(PiperSimInitialTest, JointsAndEndPoseReportTheInitialPose) {
  const Joints initial = {0.2, 0.2, -0.2, 0.3, -0.2, 0.5};
  start({"--quiet", "--initial", "0.2,0.2,-0.2,0.3,-0.2,0.5"});
  ASSERT_TRUE(wait_for([this] { return heard_.joint_pairs == 0x07 && heard_.status_seen; }, 1s));
  for (std::size_t i = 0; i < initial.size(); ++i)
    EXPECT_NEAR(heard_.joints[i], initial[i], kWireRad) << "joint " << i + 1;
  // Spec §9 test vector (new DH): 65.854, 7.898, 285.650 mm; 68.511, 41.469, 83.347°.
  EXPECT_NEAR(heard_.pose.x_m, 0.065854, 2e-6);
  EXPECT_NEAR(heard_.pose.y_m, 0.007898, 2e-6);
  EXPECT_NEAR(heard_.pose.z_m, 0.285650, 2e-6);
  constexpr double kDegPerRad = 180 / std::numbers::pi;
  EXPECT_NEAR(heard_.pose.rx_rad * kDegPerRad, 68.511, 2e-3);
  EXPECT_NEAR(heard_.pose.ry_rad * kDegPerRad, 41.469, 2e-3);
  EXPECT_NEAR(heard_.pose.rz_rad * kDegPerRad, 83.347, 2e-3);
  EXPECT_EQ(heard_.status.ctrl_mode, ControlMode::kStandby);
  EXPECT_EQ(heard_.status.arm_status, 0);
}

TEST_F(PiperSimInitialTest, PlainDhReportsTheOldFirmwarePose) {
  start({"--quiet", "--dh", "plain"});
  ASSERT_TRUE(wait_for([this] { return heard_.status_seen && heard_.frames > 20; }, 1s));
  // Spec §9: q = 0 with the old table: 54.953, 0, 203.387 mm.
  EXPECT_NEAR(heard_.pose.x_m, 0.054953, 2e-6);
  EXPECT_NEAR(heard_.pose.z_m, 0.203387, 2e-6);
}

TEST_F(PiperSimTest, MotorsStartDisabledAndFollowTheEnableFrame) {
  ASSERT_TRUE(wait_for([this] { return heard_.low_seen == 0x3F; }, 1s));
  EXPECT_TRUE(heard_.none_enabled());
  enable_all();
  send(MotorEnable{.motor = 3, .enable = false});
  EXPECT_TRUE(wait_for([this] { return (heard_.low[2].status_bits & kEnabledBit) == 0; }, 500ms));
  EXPECT_NE(heard_.low[1].status_bits & kEnabledBit, 0);
  listen_for(100ms);
  EXPECT_TRUE(heard_.replies_of<SetAck>().empty()) << "0x471 has no acknowledge";
}

// --- motion -----------------------------------------------------------------------------------

TEST_F(PiperSimTest, MoveJMovesAtTheCommandedSpeedPercentage) {
  enable_all();
  const auto move = [this](double target, std::uint8_t percent, double& peak_speed) {
    mode(MoveMode::kJ, percent);
    send_joint_targets({target, 0, 0, 0, 0, 0});
    const auto started = Clock::now();
    peak_speed = 0;
    const bool arrived = wait_for(
        [&] {
          peak_speed = std::max(peak_speed, std::abs(heard_.high[0].speed_rad_s));
          return std::abs(heard_.joints[0] - target) < 1e-3 && heard_.high[0].speed_rad_s == 0;
        },
        3s);
    EXPECT_TRUE(arrived) << "joint 1 did not reach " << target << " at " << int{percent} << " %";
    return std::chrono::duration<double>(Clock::now() - started).count();
  };
  double peak_20 = 0;
  double peak_10 = 0;
  const double time_20 = move(0.3, 20, peak_20);  // 3 rad/s × 20 %: 0.6 rad/s, ≈ 0.62 s
  const double time_10 = move(0.0, 10, peak_10);  // 0.3 rad/s, ≈ 1.06 s
  EXPECT_NEAR(peak_20, 0.6, 0.03);
  EXPECT_NEAR(peak_10, 0.3, 0.015);
  EXPECT_GT(time_10 / time_20, 1.4);
  EXPECT_LT(time_10 / time_20, 2.2);
  EXPECT_EQ(heard_.status.motion_status, 0);
  EXPECT_EQ(heard_.status.mode_feed, MoveMode::kJ);
}

TEST_F(PiperSimTest, HighFollowTracksWithoutTheSpeedPercentage) {
  enable_all();
  mode(MoveMode::kJ, 10, /*mit=*/true);
  send_joint_targets({0.5, 0, 0, 0, 0, 0});
  // At 10 % this takes 1.7 s; high-follow needs ≈ 0.35 s.
  EXPECT_TRUE(wait_until_at({0.5, 0, 0, 0, 0, 0}, 900ms));
}

TEST_F(PiperSimTest, MotionNeedsCanCommandModeAndPower) {
  send_joint_targets({0.3, 0, 0, 0, 0, 0});  // standby, disabled: nothing moves
  listen_for(200ms);
  EXPECT_NEAR(heard_.joints[0], 0.0, kWireRad);
  mode(MoveMode::kJ, 100);
  send_joint_targets({0.3, 0, 0, 0, 0, 0});  // disabled: still nothing
  listen_for(200ms);
  EXPECT_NEAR(heard_.joints[0], 0.0, kWireRad);
  EXPECT_EQ(heard_.status.ctrl_mode, ControlMode::kCanCommand);
}

TEST_F(PiperSimTest, TargetBeyondALimitReportsStatus4AndIsClamped) {
  enable_all();
  mode(MoveMode::kJ, 100);
  send_joint_targets({0, 0, 0, 0, 0, -3.0});  // J6 limit −2.09439
  ASSERT_TRUE(wait_for([this] { return heard_.status.arm_status == 0x04; }, 500ms));
  EXPECT_EQ(heard_.status.angle_limit_bits, 0x20);
  EXPECT_NEAR(state()["joints"][5]["target_rad"].get<double>(), -2.09439, 1e-9);
  send_joint_targets({0, 0, 0, 0, 0, -0.1});  // back within the limits
  EXPECT_TRUE(wait_for([this] { return heard_.status.arm_status == 0 && heard_.status.angle_limit_bits == 0; }, 500ms));
}

TEST_F(PiperSimTest, MitFramesPullAJointTowardTheirPosition) {
  enable_all();
  const MitControl command{.joint = 6, .position_rad = 0.5, .velocity_rad_s = 0, .kp = 10, .kd = 0.8, .torque = 0};
  send(command);  // not in MIT mode yet: ignored
  listen_for(150ms);
  EXPECT_NEAR(heard_.joints[5], 0.0, kWireRad);
  mode(MoveMode::kMit, 0, /*mit=*/true);
  send(command);
  EXPECT_TRUE(wait_for([this] { return std::abs(heard_.joints[5] - 0.5) < 0.01; }, 1500ms)) << heard_.joints[5];
  EXPECT_EQ(heard_.status.mode_feed, MoveMode::kMit);
  EXPECT_NEAR(heard_.joints[0], 0.0, kWireRad) << "joints without MIT frames hold";
}

TEST_F(PiperSimTest, EmergencyStopBrakesAndIgnoresMotionUntilResume) {
  enable_all();
  mode(MoveMode::kJ, 100);
  send_joint_targets({1.0, 0, 0, 0, 0, 0});
  ASSERT_TRUE(wait_for([this] { return heard_.joints[0] > 0.1; }, 1s));
  send(MotionControl{.emergency_stop = EmergencyStop::kStop});
  ASSERT_TRUE(wait_for([this] { return heard_.status.arm_status == 0x01; }, 300ms));
  ASSERT_TRUE(wait_for([this] { return heard_.high[0].speed_rad_s == 0; }, 1s)) << "joint 1 does not stop";
  const double stopped_at = heard_.joints[0];
  EXPECT_LT(stopped_at, 0.9);
  send_joint_targets({0.0, 0, 0, 0, 0, 0});  // ignored while stopped
  listen_for(300ms);
  EXPECT_NEAR(heard_.joints[0], stopped_at, kWireRad);
  EXPECT_TRUE(heard_.all_enabled()) << "the e-stop brakes; it does not de-power";

  send(MotionControl{.emergency_stop = EmergencyStop::kResume});
  EXPECT_TRUE(wait_for([this] { return heard_.status.arm_status == 0 && heard_.none_enabled(); }, 500ms));
  EXPECT_EQ(heard_.status.ctrl_mode, ControlMode::kStandby);
  EXPECT_FALSE(state()["estop"].get<bool>());
}

// A joint the e-stop catches as it runs fast toward its limit (high-follow ramps 4× steeper than
// the brake) stops at the limit, not beyond it, and resume leaves no error behind: the SDK saw J2
// stop 0.052° below 0° and "target exceeds limit" stay after resume.
TEST_F(PiperSimInitialTest, EmergencyStopNeverBrakesAJointPastItsLimit) {
  start({"--quiet", "--initial", "0,1.2,0,0,0,0"});
  enable_all();
  mode(MoveMode::kJ, 100, /*mit=*/true);
  send_joint_targets({0, 0, 0, 0, 0, 0});  // J2 down to its lower limit, 0
  ASSERT_TRUE(wait_for([this] { return heard_.joints[1] < 0.5; }, 1s));
  send(MotionControl{.emergency_stop = EmergencyStop::kStop});
  ASSERT_TRUE(wait_for([this] { return heard_.status.arm_status == 0x01; }, 300ms));
  ASSERT_TRUE(wait_for([this] { return heard_.high[1].speed_rad_s == 0; }, 1s)) << "joint 2 does not stop";
  listen_for(20ms);
  EXPECT_GE(heard_.joints[1], -kWireRad) << "J2 braked below its lower limit";
  EXPECT_EQ(heard_.status.angle_limit_bits, 0);

  send(MotionControl{.emergency_stop = EmergencyStop::kResume});
  EXPECT_TRUE(wait_for([this] { return heard_.status.arm_status == 0 && heard_.none_enabled(); }, 500ms))
      << "arm status " << int{heard_.status.arm_status};
  EXPECT_EQ(heard_.status.angle_limit_bits, 0);
}

// MOVE P 20 mm from a pose by the wrist singularity (J5 = 0.02): the arm takes the solution
// nearest its joints (J4 stays on its side) instead of swinging J4 and J6 round by 140°.
TEST_F(PiperSimInitialTest, MovePNearTheWristSingularityTakesTheNearestSolution) {
  start({"--quiet", "--initial", "0,0.5,-1.0,0.8,0.02,-0.8"});
  CartesianPose target = forward_kinematics({0, 0.5, -1.0, 0.8, 0.02, -0.8}, DhVariant::kOffset);
  target.y_m -= 0.02;
  enable_all();
  mode(MoveMode::kP, 100);
  send_pose(target);
  ASSERT_TRUE(wait_for([this] { return heard_.status.motion_status == 1; }, 500ms));
  ASSERT_TRUE(wait_for([this] { return heard_.status.motion_status == 0; }, 3s));
  listen_for(20ms);
  EXPECT_NEAR(heard_.pose.y_m, target.y_m, 1e-4);
  EXPECT_GT(heard_.joints[3], 0.0) << "J4 swung to the far solution";
  EXPECT_LT(std::abs(heard_.joints[3] - 0.8), 1.05);
}

// The vendor SDK's session against the simulator (tests/conformance/piper/sdk_sim_transcript.json,
// recorded by tests/conformance/piper/generate/sdk_against_sim.py), replayed frame for frame: the
// same frames bring the arm to the same joints wherever the outcome does not depend on when a
// frame went out. The SDK stopped J2 with the e-stop once it was below 30° (30000 m°); where it
// stops depends on that moment, so only the limit is checked there.
TEST_F(PiperSimTest, TheSdkTranscriptReplays) {
  std::ifstream file(ROBOTD_SOURCE_DIR "/tests/conformance/piper/sdk_sim_transcript.json");
  ASSERT_TRUE(file) << "sdk_sim_transcript.json is missing";
  const nlohmann::json transcript = nlohmann::json::parse(file);
  constexpr double kMilliDeg = std::numbers::pi / 180000;
  constexpr double kJointToleranceRad = 50 * kMilliDeg;  // 0.05°: the IK's own tolerance, then the wire
  const auto at_rest = [this] {
    return heard_.status.motion_status == 0 && heard_.joint_pairs == 0x07 &&
           std::all_of(heard_.high.begin(), heard_.high.end(),
                       [](const HighSpeedInfo& h) { return h.speed_rad_s == 0; });
  };
  for (const nlohmann::json& step : transcript.at("steps")) {
    const std::string name = step.at("step");
    SCOPED_TRACE(name);
    for (const nlohmann::json& frame : step.at("sent")) {
      std::vector<std::uint8_t> bytes;
      const std::string hex = frame.at("data");
      for (std::size_t at = 0; at + 1 < hex.size(); at += 3) {  // "01 02 …"
        bytes.push_back(static_cast<std::uint8_t>(std::stoi(hex.substr(at, 2), nullptr, 16)));
      }
      send_message(transport::classic_frame(frame.at("id").get<std::uint32_t>(), bytes));
    }
    if (name == "move p 20 mm") continue;  // arrives in the next step
    if (name == "high-follow j2 down") {
      ASSERT_TRUE(wait_for([this] { return heard_.joints[1] < 30000 * kMilliDeg; }, 2s));
      continue;
    }
    if (name == "enable" || name == "enable again") {
      ASSERT_TRUE(wait_for([this] { return heard_.all_enabled(); }, 1s));
      continue;
    }
    if (name == "mit") {  // MIT dynamics: where joint 6 is at a given moment depends on timing
      EXPECT_TRUE(wait_for([this] { return std::abs(heard_.joints[5] - 0.5) < 0.01; }, 2s)) << heard_.joints[5];
      continue;
    }
    listen_for(30ms);
    heard_.joint_pairs = 0;
    ASSERT_TRUE(wait_for(at_rest, 5s));
    EXPECT_EQ(heard_.status.arm_status, step.at("status").at("arm_status").get<int>());
    if (name == "e-stop" || name == "resume") {
      EXPECT_GE(heard_.joints[1], -kWireRad) << "J2 below its lower limit";
      EXPECT_EQ(heard_.status.angle_limit_bits, 0);
      continue;
    }
    for (std::size_t j = 0; j < kArmJoints; ++j) {
      EXPECT_NEAR(heard_.joints[j], step.at("joints_mdeg").at(j).get<double>() * kMilliDeg, kJointToleranceRad)
          << "joint " << j + 1;
    }
  }
}

TEST_F(PiperSimInitialTest, MovePReachesThePose) {
  start({"--quiet", "--initial", "0,1.0,-1.0,0,0.3,0"});
  const CartesianPose target = forward_kinematics({0.2, 1.2, -1.1, 0.1, 0.4, -0.2}, DhVariant::kOffset);
  enable_all();
  mode(MoveMode::kP, 100);
  send_pose(target);
  ASSERT_TRUE(wait_for([this] { return heard_.status.motion_status == 1; }, 500ms));
  ASSERT_TRUE(wait_for([this] { return heard_.status.motion_status == 0; }, 2s));
  listen_for(20ms);
  EXPECT_NEAR(heard_.pose.x_m, target.x_m, 1e-4);
  EXPECT_NEAR(heard_.pose.y_m, target.y_m, 1e-4);
  EXPECT_NEAR(heard_.pose.z_m, target.z_m, 1e-4);
  const Eigen::Quaterniond reached(transform_of(heard_.pose).rotation());
  EXPECT_LT(reached.angularDistance(Eigen::Quaterniond(transform_of(target).rotation())), 2e-3);
  EXPECT_EQ(heard_.status.arm_status, 0);
}

TEST_F(PiperSimTest, MovePWithoutAnIkSolutionReportsStatus2AndStays) {
  enable_all();
  mode(MoveMode::kP, 100);
  send_pose(CartesianPose{.x_m = 2.0, .y_m = 0, .z_m = 0.2, .rx_rad = 0, .ry_rad = 0, .rz_rad = 0});
  EXPECT_TRUE(wait_for([this] { return heard_.status.arm_status == 0x02; }, 1s));
  listen_for(100ms);
  for (double q : heard_.joints) EXPECT_NEAR(q, 0.0, kWireRad);
}

TEST_F(PiperSimInitialTest, MoveLKeepsTheFlangeOnTheLine) {
  start({"--quiet", "--initial", "0,1.0,-1.0,0,0.3,0"});
  const CartesianPose from = forward_kinematics({0, 1.0, -1.0, 0, 0.3, 0}, DhVariant::kOffset);
  CartesianPose to = from;
  to.z_m += 0.05;
  enable_all();
  mode(MoveMode::kL, 20);  // 0.1 m/s: 0.5 s
  send_pose(to);
  double worst_off_line = 0;
  ASSERT_TRUE(wait_for([this] { return heard_.status.motion_status == 1; }, 500ms));
  ASSERT_TRUE(wait_for(
      [&] {
        worst_off_line =
            std::max({worst_off_line, std::abs(heard_.pose.x_m - from.x_m), std::abs(heard_.pose.y_m - from.y_m)});
        return heard_.status.motion_status == 0;
      },
      2s));
  EXPECT_LT(worst_off_line, 2e-3);
  EXPECT_NEAR(heard_.pose.z_m, to.z_m, 1e-4);
}

TEST_F(PiperSimInitialTest, MoveCPassesTheMiddlePointToTheEnd) {
  start({"--quiet", "--initial", "0,1.0,-1.0,0,0.3,0"});
  const CartesianPose start_pose = forward_kinematics({0, 1.0, -1.0, 0, 0.3, 0}, DhVariant::kOffset);
  const CartesianPose middle = forward_kinematics({0.15, 1.1, -1.0, 0, 0.3, 0}, DhVariant::kOffset);
  const CartesianPose end = forward_kinematics({0.3, 1.0, -1.0, 0, 0.3, 0}, DhVariant::kOffset);
  enable_all();
  mode(MoveMode::kC, 100);
  send_pose(start_pose);
  send(MoveCPoint{.index = 1});
  send_pose(middle);
  send(MoveCPoint{.index = 2});
  send_pose(end);
  send(MoveCPoint{.index = 3});
  double closest_to_middle = 1.0;
  ASSERT_TRUE(wait_for([this] { return heard_.status.motion_status == 1; }, 500ms));
  ASSERT_TRUE(wait_for(
      [&] {
        closest_to_middle = std::min(
            closest_to_middle,
            std::hypot(heard_.pose.x_m - middle.x_m, heard_.pose.y_m - middle.y_m, heard_.pose.z_m - middle.z_m));
        return heard_.status.motion_status == 0;
      },
      2s));
  EXPECT_LT(closest_to_middle, 5e-3);
  // The status and the pose come in frames of their own: the last pose may follow the status.
  EXPECT_TRUE(wait_for(
      [&] {
        return std::fabs(heard_.pose.x_m - end.x_m) <= 1e-4 && std::fabs(heard_.pose.y_m - end.y_m) <= 1e-4 &&
               std::fabs(heard_.pose.z_m - end.z_m) <= 1e-4;
      },
      500ms));
  EXPECT_NEAR(heard_.pose.x_m, end.x_m, 1e-4);
  EXPECT_NEAR(heard_.pose.y_m, end.y_m, 1e-4);
  EXPECT_NEAR(heard_.pose.z_m, end.z_m, 1e-4);
}

TEST_F(PiperSimTest, GripperMovesToTheStrokeAndPressesWhileClosing) {
  send(GripperControl{.stroke_m = 0.05, .effort_nm = 1.0, .enable = GripperEnable::kEnable, .set_zero = false});
  ASSERT_TRUE(wait_for([this] { return (heard_.gripper.status_bits & kEnabledBit) != 0; }, 500ms));
  ASSERT_TRUE(wait_for([this] { return std::abs(heard_.gripper.stroke_m - 0.05) < 1e-6; }, 1500ms));
  send(GripperControl{.stroke_m = 0.02, .effort_nm = 1.0, .enable = GripperEnable::kEnable, .set_zero = false});
  EXPECT_TRUE(wait_for([this] { return std::abs(heard_.gripper.effort_nm - 1.0) < 1e-3; }, 300ms));
  EXPECT_TRUE(wait_for([this] { return std::abs(heard_.gripper.stroke_m - 0.02) < 1e-6; }, 1s));
  send(GripperControl{.stroke_m = 0.2, .effort_nm = 1.0, .enable = GripperEnable::kEnable, .set_zero = false});
  EXPECT_TRUE(wait_for([this] { return std::abs(heard_.gripper.stroke_m - 0.07) < 1e-6; }, 1500ms))
      << "beyond the 70 mm stroke: stops there";
}

// --- requests and replies ---------------------------------------------------------------------

TEST_F(PiperSimTest, EveryQueryGetsItsReply) {
  for (std::uint8_t joint = 1; joint <= kArmJoints; ++joint) {
    send(JointLimitQuery{.joint = joint, .acceleration = false});
    send(JointLimitQuery{.joint = joint, .acceleration = true});
  }
  send(ParamEnquiry{.query = 1});
  send(ParamEnquiry{.query = 2});
  send(ParamEnquiry{.query = 4});
  send_message(firmware_request());
  ASSERT_TRUE(wait_for([this] { return heard_.replies.size() >= 15 && heard_.firmware_frames >= 11; }, 1s))
      << heard_.replies.size() << " replies, " << heard_.firmware_frames << " firmware frames";
  const auto limits = heard_.replies_of<JointLimitReply>();
  ASSERT_EQ(limits.size(), 6U);
  for (std::size_t i = 0; i < limits.size(); ++i) {
    EXPECT_EQ(int{limits[i].joint}, static_cast<int>(i) + 1);
    EXPECT_NEAR(limits[i].max_speed_rad_s, 3.0, 1e-3);
  }
  EXPECT_NEAR(limits[1].max_angle_rad, 3.14, 2e-3);
  EXPECT_NEAR(limits[2].min_angle_rad, -2.967, 2e-3);
  const auto accelerations = heard_.replies_of<JointAccReply>();
  ASSERT_EQ(accelerations.size(), 6U);
  EXPECT_NEAR(accelerations[0].max_acc_rad_s2, 5.0, 1e-2);
  EXPECT_EQ(heard_.replies_of<EndVelAccReply>().size(), 1U);
  EXPECT_EQ(heard_.replies_of<CrashProtectionReply>().size(), 1U);
  const auto gripper = heard_.replies_of<GripperParamReply>();
  ASSERT_EQ(gripper.size(), 1U);
  EXPECT_EQ(gripper[0].params.max_range_mm, 70);
  EXPECT_EQ(heard_.firmware_frames, 11);
  EXPECT_EQ(heard_.firmware.size(), 88U);
  EXPECT_EQ(heard_.firmware.substr(0, 8), "H-V1.2-1");
  EXPECT_EQ(heard_.firmware.substr(32, 6), "ARM_MC");
  EXPECT_EQ(software_version(heard_.firmware), "S-V1.8-2");
}

TEST_F(PiperSimInitialTest, TheFirmwareVersionIsConfigurable) {
  start({"--quiet", "--firmware", "S-V1.8-9"});
  send_message(firmware_request());
  ASSERT_TRUE(wait_for([this] { return heard_.firmware_frames >= 11; }, 1s));
  EXPECT_EQ(software_version(heard_.firmware), "S-V1.8-9");
  EXPECT_EQ(sim_->control({{"op", "state"}})["firmware"], "S-V1.8-9");
}

TEST_F(PiperSimTest, SetCommandsAreAcknowledgedAndTakeEffect) {
  ASSERT_TRUE(sim_->control({{"op", "set_joint"}, {"joint", 1}, {"position_rad", 0.4}})["ok"].get<bool>());
  send(JointLimitSet{.joint = 1, .max_angle_rad = 1.0, .min_angle_rad = -1.0, .max_speed_rad_s = std::nullopt});
  send(JointConfig{.joint = 1, .set_zero = true, .apply_max_acc = true, .max_acc_rad_s2 = 2.5, .clear_error = false});
  send(EndVelAccSet{.values = {.max_linear_velocity_m_s = 0.3,
                               .max_angular_velocity_rad_s = std::nullopt,
                               .max_linear_acceleration_m_s2 = std::nullopt,
                               .max_angular_acceleration_rad_s2 = std::nullopt}});
  send(CrashProtectionSet{.levels = {1, 2, 3, 4, 5, 6}});
  ASSERT_TRUE(wait_for([this] { return heard_.replies_of<SetAck>().size() >= 4; }, 1s));
  const auto acks = heard_.replies_of<SetAck>();
  ASSERT_EQ(acks.size(), 4U);
  EXPECT_EQ(acks[0].command, 0x74);
  EXPECT_EQ(acks[1].command, 0x75);
  EXPECT_TRUE(acks[1].zero_set);
  EXPECT_EQ(acks[2].command, 0x79);
  EXPECT_EQ(acks[3].command, 0x7A);
  EXPECT_TRUE(wait_for([this] { return std::abs(heard_.joints[0]) < kWireRad; }, 300ms)) << "0x475 set zero";

  heard_.replies.clear();
  send(JointLimitQuery{.joint = 1, .acceleration = false});
  send(JointLimitQuery{.joint = 1, .acceleration = true});
  send(ParamEnquiry{.query = 1});
  send(ParamEnquiry{.query = 2});
  ASSERT_TRUE(wait_for([this] { return heard_.replies.size() >= 4; }, 1s));
  EXPECT_NEAR(heard_.replies_of<JointLimitReply>().at(0).max_angle_rad, 1.0, 2e-3);
  EXPECT_NEAR(heard_.replies_of<JointAccReply>().at(0).max_acc_rad_s2, 2.5, 1e-2);
  EXPECT_NEAR(heard_.replies_of<EndVelAccReply>().at(0).values.max_linear_velocity_m_s.value_or(0), 0.3, 1e-3);
  EXPECT_EQ(heard_.replies_of<CrashProtectionReply>().at(0).levels[5], 6);

  heard_.replies.clear();
  send(ParamEnquiry{.query = 0, .setting = 2});  // reset the joint limits: acknowledged with 0x77
  send(JointLimitQuery{.joint = 1, .acceleration = false});
  ASSERT_TRUE(wait_for([this] { return heard_.replies.size() >= 2; }, 1s));
  EXPECT_EQ(heard_.replies_of<SetAck>().at(0).command, 0x77);
  EXPECT_NEAR(heard_.replies_of<JointLimitReply>().at(0).max_angle_rad, 2.6179, 2e-3);
}

// --- the control channel ----------------------------------------------------------------------

TEST_F(PiperSimTest, SilenceStopsTheFeedbackForAWhile) {
  listen_for(50ms);
  ASSERT_TRUE(sim_->control({{"op", "silence"}, {"ms", 400}})["ok"].get<bool>());
  listen_for(20ms);  // frames already on their way
  heard_.frames = 0;
  listen_for(250ms);
  EXPECT_EQ(heard_.frames, 0);
  EXPECT_TRUE(wait_for([this] { return heard_.frames > 100; }, 1s)) << "the feedback did not come back";
  ASSERT_TRUE(sim_->control({{"op", "silence"}, {"ms", 5000}})["ok"].get<bool>());
  ASSERT_TRUE(sim_->control({{"op", "silence"}, {"ms", 0}})["ok"].get<bool>());  // ends it now
  heard_.frames = 0;
  EXPECT_TRUE(wait_for([this] { return heard_.frames > 100; }, 500ms));
}

TEST_F(PiperSimTest, DroppedRepliesAreNotSent) {
  ASSERT_TRUE(sim_->control({{"op", "drop_replies"}, {"enabled", true}})["ok"].get<bool>());
  send(JointLimitQuery{.joint = 1, .acceleration = false});
  send(JointConfig{.joint = 1, .set_zero = false, .clear_error = true});
  send_message(firmware_request());
  listen_for(300ms);
  EXPECT_TRUE(heard_.replies.empty());
  EXPECT_EQ(heard_.firmware_frames, 0);
  ASSERT_TRUE(sim_->control({{"op", "drop_replies"}, {"enabled", false}})["ok"].get<bool>());
  send(JointLimitQuery{.joint = 1, .acceleration = false});
  EXPECT_TRUE(wait_for([this] { return heard_.replies_of<JointLimitReply>().size() == 1; }, 500ms));
}

TEST_F(PiperSimTest, RaisedErrorsAreReportedUntilCleared) {
  ASSERT_TRUE(sim_->control({{"op", "raise_error"}, {"arm_status", 7}})["ok"].get<bool>());
  EXPECT_TRUE(wait_for([this] { return heard_.status.arm_status == 0x07; }, 300ms));
  ASSERT_TRUE(sim_->control({{"op", "clear_error"}})["ok"].get<bool>());
  EXPECT_TRUE(wait_for([this] { return heard_.status.arm_status == 0; }, 300ms));

  ASSERT_TRUE(sim_->control({{"op", "raise_error"}, {"joint", 2}, {"driver_status_bits", 0x24}})["ok"].get<bool>());
  ASSERT_TRUE(sim_->control({{"op", "raise_error"}, {"joint", 4}, {"comm_error", true}})["ok"].get<bool>());
  EXPECT_TRUE(wait_for([this] { return (heard_.low[1].status_bits & 0x24) == 0x24; }, 300ms));
  EXPECT_TRUE(wait_for([this] { return heard_.status.comm_error_bits == 0x08; }, 300ms));
  send(JointConfig{.joint = 2, .set_zero = false, .clear_error = true});
  EXPECT_TRUE(wait_for([this] { return (heard_.low[1].status_bits & 0x24) == 0; }, 300ms)) << "0x475 clear error";
  EXPECT_EQ(heard_.status.comm_error_bits, 0x08) << "only joint 2 was cleared";

  ASSERT_TRUE(sim_->control({{"op", "raise_error"}, {"arm_status", 9}})["ok"].get<bool>());
  send(MotionControl{.emergency_stop = EmergencyStop::kResume});
  EXPECT_TRUE(wait_for([this] { return heard_.status.arm_status == 0 && heard_.status.comm_error_bits == 0; }, 300ms))
      << "0x150 resume clears everything";
}

TEST_F(PiperSimTest, DisconnectClosesTheLinkAndTheBusComesBack) {
  listen_for(50ms);
  ASSERT_TRUE(sim_->control({{"op", "disconnect"}, {"ms", 300}})["ok"].get<bool>());
  CanIo result = CanIo::kNone;
  const auto deadline = Clock::now() + 500ms;
  while (result != CanIo::kClosed && Clock::now() < deadline) {
    result = drain();
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_EQ(result, CanIo::kClosed);
  EXPECT_FALSE(state()["bus_open"].get<bool>());
  bool reconnected = false;
  for (int attempt = 0; attempt < 100 && !reconnected; ++attempt) {
    std::this_thread::sleep_for(20ms);
    link_ = transport::make_can_transport(standin(sim_->bus_path()));
    reconnected = static_cast<bool>(link_->open());
  }
  ASSERT_TRUE(reconnected);
  heard_ = Heard{};
  EXPECT_TRUE(wait_for([this] { return heard_.frames > 100; }, 1s));
}

TEST_F(PiperSimTest, GarbageFramesNeverDecode) {
  listen_for(50ms);
  heard_ = Heard{};
  ASSERT_TRUE(sim_->control({{"op", "garbage"}, {"frames", 300}})["ok"].get<bool>());
  listen_for(300ms);
  EXPECT_GE(heard_.undecodable, 280);  // 10 per ms; a few may fall out of a full socket buffer
  EXPECT_LE(heard_.undecodable, 300);
  EXPECT_GT(heard_.frames - heard_.undecodable, 500) << "the feedback keeps flowing";
}

TEST_F(PiperSimTest, GarbageFromTheHostDoesNotBreakTheSimulator) {
  std::mt19937 random(42);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int i = 0; i < 3000; ++i) {
    CanMessage message;
    message.id = std::uniform_int_distribution<std::uint32_t>(0x100, 0x4FF)(random);
    if (i % 3 == 0) message.id = std::uniform_int_distribution<std::uint32_t>(0x150, 0x15F)(random);
    if (i % 7 == 0) {
      message.extended = true;
      message.id = std::uniform_int_distribution<std::uint32_t>(0, 0x1FFFFFFF)(random);
    }
    message.length = static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 8)(random));
    for (std::size_t k = 0; k < message.length; ++k) message.data[k] = static_cast<std::uint8_t>(byte(random));
    (void)link_->send(message);  // the socket may be full: dropped, as on a busy bus
    if (i % 100 == 0) drain();
  }
  heard_ = Heard{};
  listen_for(300ms);
  EXPECT_GT(heard_.frames, 500) << "the feedback keeps flowing";
  const auto reply = state();
  EXPECT_TRUE(reply["ok"].get<bool>());
  send(JointLimitQuery{.joint = 1, .acceleration = false});
  EXPECT_TRUE(wait_for([this] { return !heard_.replies_of<JointLimitReply>().empty(); }, 500ms));
}

TEST_F(PiperSimTest, CountersCountHostFramesById) {
  ASSERT_TRUE(sim_->control({{"op", "reset_counters"}})["ok"].get<bool>());
  for (int i = 0; i < 10; ++i) send_joint_targets({0, 0, 0, 0, 0, 0});
  send(ModeControl{});
  listen_for(100ms);
  const auto reply = state();
  EXPECT_EQ(reply["frames_received"]["0x155"], 10);
  EXPECT_EQ(reply["frames_received"]["0x157"], 10);
  EXPECT_EQ(reply["frames_received"]["0x151"], 1);
  EXPECT_GT(reply["frames_sent"].get<int>(), 200);
}

TEST_F(PiperSimTest, SetJointPutsAJointWhereTheTestWantsIt) {
  ASSERT_TRUE(sim_->control({{"op", "set_joint"}, {"joint", 4}, {"position_rad", -0.7}})["ok"].get<bool>());
  EXPECT_TRUE(wait_for([this] { return std::abs(heard_.joints[3] + 0.7) < kWireRad; }, 300ms));
  const auto refused = sim_->control({{"op", "set_joint"}, {"joint", 2}, {"position_rad", -1.0}});
  EXPECT_FALSE(refused["ok"].get<bool>());
  EXPECT_NE(refused["error"].get<std::string>().find("limits"), std::string::npos) << refused.dump();
}

TEST_F(PiperSimTest, BadRequestsGetAnErrorThatSaysWhatIsExpected) {
  const auto expect_error = [this](const nlohmann::json& request, const std::string& mentions) {
    const auto reply = sim_->control(request);
    EXPECT_FALSE(reply["ok"].get<bool>()) << request.dump();
    EXPECT_NE(reply["error"].get<std::string>().find(mentions), std::string::npos) << reply.dump();
  };
  expect_error({{"op", "fly"}}, "unknown op");
  expect_error({{"nop", 1}}, "\"op\"");
  expect_error({{"op", "silence"}}, "\"ms\"");
  expect_error({{"op", "silence"}, {"ms", -5}}, "0 … 3600000");
  expect_error({{"op", "drop_replies"}, {"enabled", 1}}, "true or false");
  expect_error({{"op", "garbage"}, {"frames", 0}}, "\"frames\"");
  expect_error({{"op", "raise_error"}, {"joint", 9}, {"comm_error", true}}, "\"joint\"");
  expect_error({{"op", "raise_error"}}, "needs one of");
  expect_error({{"op", "state"}, {"verbose", true}}, "does not take \"verbose\"");
  expect_error({{"op", "set_joint"}, {"joint", 1}}, "position_rad");
  EXPECT_TRUE(state()["ok"].get<bool>()) << "still serving";
}

// --- the process ------------------------------------------------------------------------------

TEST_F(PiperSimTest, SigtermEndsItCleanly) { EXPECT_EQ(sim_->terminate(), 0); }

TEST_F(PiperSimTest, KilledAndRestartedItServesTheSamePath) {
  sim_->kill_hard();
  CanIo result = CanIo::kNone;
  for (int i = 0; i < 500 && result != CanIo::kClosed; ++i) {
    result = drain();
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_EQ(result, CanIo::kClosed) << "the link ends with the simulator";
  sim_->restart();
  connect();
  EXPECT_TRUE(wait_for([this] { return heard_.frames > 100; }, 1s));
}

// --- leader and id offsets ----------------------------------------------------------------------

// --role leader: what a leader arm sends (0x151 with 0xAD, 0x155–0x157 from its joints, 0x159) and
// no feedback; it keeps a 0x470 and takes it at its next start.
TEST_F(PiperSimTest, ALeaderSendsItsCommandsNoFeedbackAndTakesA470AtARestart) {
  start({"--quiet", "--role", "leader"});
  ASSERT_TRUE(sim_->control({{"op", "set_joint"}, {"joint", 4}, {"position_rad", 0.6}})["ok"].get<bool>());
  ASSERT_TRUE(wait_for(
      [this] {
        const auto pairs = heard_.replies_of<JointTargetPair>();
        return !heard_.replies_of<ModeControl>().empty() && !heard_.replies_of<GripperControl>().empty() &&
               std::any_of(pairs.begin(), pairs.end(), [](const JointTargetPair& pair) {
                 return pair.pair == 1 && std::abs(pair.second_rad - 0.6) < kWireRad;
               });
      },
      2s));
  const ModeControl mode = heard_.replies_of<ModeControl>().back();
  EXPECT_EQ(mode.ctrl_mode, ControlMode::kCanCommand);
  EXPECT_EQ(mode.move_mode, MoveMode::kJ);
  EXPECT_TRUE(mode.mit) << "a leader sets its follower to high follow (0xAD)";
  EXPECT_FALSE(heard_.status_seen);
  EXPECT_EQ(heard_.joint_pairs, 0);
  EXPECT_EQ(heard_.low_seen, 0);

  send(MasterSlaveConfig{.linkage = 0xFC, .feedback_offset = 0x10});
  ASSERT_TRUE(wait_for([this] { return state()["master_slave"] == 0xFC; }, 1s));
  EXPECT_EQ(state()["role"], "leader") << "0x470 waits for the arm's restart";
  const nlohmann::json restarted = sim_->control({{"op", "restart"}});
  EXPECT_EQ(restarted["role"], "follower") << restarted.dump();
  EXPECT_EQ(state()["feedback_id_offset"], 0x10);
  heard_ = Heard{};
  // Its feedback now goes out at 0x2B1–0x2B8, which a node without the offset does not decode.
  ASSERT_TRUE(wait_for([this] { return heard_.low_seen == 0x3F; }, 1s));
  EXPECT_FALSE(heard_.status_seen);
  EXPECT_GT(heard_.undecodable, 0);
}

TEST(PiperSimCommandLine, BadOptionsExitWith2) {
  EXPECT_EQ(run_to_exit({}), 2) << "no bus";
  EXPECT_EQ(run_to_exit({"--standin", "/tmp/x.sock", "--interface", "can0"}), 2);
  EXPECT_EQ(run_to_exit({"--standin", "/tmp/x.sock", "--dh", "crooked"}), 2);
  EXPECT_EQ(run_to_exit({"--standin", "/tmp/x.sock", "--initial", "0,0,0"}), 2);
  EXPECT_EQ(run_to_exit({"--standin", "/tmp/x.sock", "--initial", "0,-1,0,0,0,0"}), 2) << "J2 below 0";
  EXPECT_EQ(run_to_exit({"--standin", "/tmp/x.sock", "--firmware", "V1.8-2"}), 2);
  EXPECT_EQ(run_to_exit({"--standin", "/tmp/x.sock", "--feedback-rate-hz", "0"}), 2);
  EXPECT_EQ(run_to_exit({"--standin", "/tmp/x.sock", "--bogus"}), 2);
}

TEST(PiperSimCommandLine, ASocketInUseExitsWith2) {
  const PiperSimProcess first("", {"--quiet"});
  EXPECT_EQ(run_to_exit({"--standin", first.bus_path(), "--quiet"}), 2);
  EXPECT_EQ(run_to_exit({"--standin", PiperSimProcess::unique_path("piper-bus"), "--control", first.control_path()}),
            2);
  EXPECT_TRUE(first.control({{"op", "state"}})["ok"].get<bool>()) << "the first one is unharmed";
}

}  // namespace
}  // namespace robotd::piper
