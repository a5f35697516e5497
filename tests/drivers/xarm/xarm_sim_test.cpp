// robotd-xarm-sim as a client sees it: a real process on 127.0.0.1, spoken to over real TCP with
// the codec (the command port's frames, the report ports' packets), and steered through its
// control channel.
#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include <gtest/gtest.h>

#include "codec/xarm_codec.hpp"
#include "robotd/transport/ip_socket.hpp"
#include "xarm_sim_process.hpp"

namespace robotd::xarm {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;
using testing::XarmSimProcess;
using Clock = std::chrono::steady_clock;

constexpr auto kReplyTimeout = 1000ms;
constexpr std::uint8_t kInvalid = 0x08;
constexpr std::uint8_t kNotReady = 0x10;
constexpr std::uint8_t kWarning = 0x20;
constexpr std::uint8_t kError = 0x40;
/// fp32 on the wire: angles to about 1e-7 rad.
constexpr double kWireRad = 1e-5;

std::uint8_t reg_of(Register reg) { return static_cast<std::uint8_t>(reg); }

/// A well-conditioned xArm 6 posture (TCP about 0.4 m out, pointing down), in rad.
JointValues posture() { return {0, -0.2, -0.9, 0, 1.1, 0, 0}; }

JointMove joint_move(const JointValues& joints, double speed_rad_s = 1.0, double acc_rad_s2 = 10.0) {
  return JointMove{.joints_rad = joints, .speed_rad_s = speed_rad_s, .acc_rad_s2 = acc_rad_s2, .mvtime_s = 0};
}

/// The command count a reply carries, or -1 when it carries none.
int cmdnum(const Bytes& data) {
  const auto count = parse_cmdnum(data);
  return count ? count.value() : -1;
}

/// A request this test builds itself (the codec has builders only for what robotd sends).
Request raw_request(Register reg, Bytes params = {}) {
  return Request{.reg = reg_of(reg), .params = std::move(params)};
}

/// A command-port client: one TCP connection, its replies and motion feedback kept apart.
class Connection {
 public:
  explicit Connection(std::uint16_t port) {
    auto connected = transport::connect_tcp(transport::Endpoint{"127.0.0.1", port}, 1000ms);
    if (!connected) throw std::runtime_error(connected.error().message);
    socket_ = std::move(connected).value();
  }

  /// Sends a request; its transaction id.
  std::uint16_t send(const Request& request, std::uint16_t protocol = kProtocolPrivate) {
    const std::uint16_t id = next_id_++;
    send_raw(
        encode_frame(Frame{.transaction_id = id, .protocol = protocol, .reg = request.reg, .body = request.params}));
    return id;
  }
  void send_raw(const Bytes& bytes) {
    const std::string_view view(reinterpret_cast<const char*>(bytes.data()), bytes.size());  // NOLINT
    std::size_t offset = 0;
    while (offset < view.size()) {
      std::size_t sent = 0;
      ASSERT_NE(transport::send_some(socket_.fd(), view.substr(offset), sent), transport::SendResult::kClosed);
      offset += sent;
      if (sent == 0) std::this_thread::sleep_for(1ms);
    }
  }
  /// The next reply, or nullopt after `timeout`.
  std::optional<Reply> next_reply(std::chrono::milliseconds timeout = kReplyTimeout) {
    return next_of(replies_, timeout);
  }
  std::optional<MotionFeedback> next_feedback(std::chrono::milliseconds timeout = kReplyTimeout) {
    return next_of(feedback_, timeout);
  }
  /// Sends and waits for the reply to it (the test fails without one).
  Reply request(const Request& request, std::uint16_t protocol = kProtocolPrivate) {
    const std::uint16_t id = send(request, protocol);
    auto reply = next_reply();
    EXPECT_TRUE(reply) << "no reply to " << register_name(request.reg);
    if (!reply) return Reply{};
    EXPECT_EQ(reply->transaction_id, id);
    EXPECT_EQ(reply->reg, request.reg);
    return *reply;
  }
  /// Reads for `window`; true if the peer closed meanwhile.
  bool closed_within(std::chrono::milliseconds window) {
    const auto deadline = Clock::now() + window;
    while (!closed_ && Clock::now() < deadline) read_some(5ms);
    return closed_;
  }
  /// Whether the byte stream stopped making sense (a length field the splitter refuses).
  bool broken() const { return broken_; }

 private:
  template <class T>
  std::optional<T> next_of(std::vector<T>& queue, std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    do {  // reads at least once: a zero timeout takes what is waiting
      if (!queue.empty() || closed_ || broken_) break;
      read_some(std::clamp(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()), 0ms, 5ms));
    } while (Clock::now() < deadline);
    if (queue.empty()) return std::nullopt;
    T item = queue.front();
    queue.erase(queue.begin());
    return item;
  }
  void read_some(std::chrono::milliseconds wait) {
    if (!transport::wait_readable(socket_.fd(), wait)) return;
    std::array<std::uint8_t, 8192> bytes{};
    const ssize_t n = ::recv(socket_.fd(), bytes.data(), bytes.size(), 0);
    if (n <= 0) {
      closed_ = n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK);
      return;
    }
    frames_.append(ByteView(bytes.data(), static_cast<std::size_t>(n)));
    while (true) {
      auto frame = frames_.next();
      if (!frame) {
        broken_ = true;
        return;
      }
      if (!frame.value()) return;
      if (is_motion_feedback(*frame.value())) {
        auto feedback = parse_motion_feedback(*frame.value());
        ASSERT_TRUE(feedback) << feedback.error().message;
        feedback_.push_back(feedback.value());
      } else {
        auto reply = parse_reply(*frame.value());
        ASSERT_TRUE(reply) << reply.error().message;
        replies_.push_back(reply.value());
      }
    }
  }

  transport::Socket socket_;
  FrameSplitter frames_;
  std::vector<Reply> replies_;
  std::vector<MotionFeedback> feedback_;
  std::uint16_t next_id_ = 1;
  bool closed_ = false;
  bool broken_ = false;
};

/// A report-port client.
class ReportReader {
 public:
  ReportReader(std::uint16_t port, ReportKind kind) : kind_(kind) {
    auto connected = transport::connect_tcp(transport::Endpoint{"127.0.0.1", port}, 1000ms);
    if (!connected) throw std::runtime_error(connected.error().message);
    socket_ = std::move(connected).value();
  }

  /// The packets that arrive within `window` (after dropping what waited).
  std::vector<Bytes> packets_for(std::chrono::milliseconds window) {
    read_for(0ms);
    packets_.clear();
    read_for(window);
    std::vector<Bytes> taken;
    taken.swap(packets_);
    return taken;
  }
  /// The next packet sent after now, parsed.
  std::optional<Report> fresh(std::chrono::milliseconds timeout = 500ms) {
    read_for(0ms);
    packets_.clear();
    const auto deadline = Clock::now() + timeout;
    while (packets_.empty() && !closed_ && Clock::now() < deadline) read_for(5ms);
    if (packets_.empty()) return std::nullopt;
    auto report = parse_report(packets_.front(), kind_);
    EXPECT_TRUE(report) << report.error().message;
    if (!report) return std::nullopt;
    return report.value();
  }
  bool closed_within(std::chrono::milliseconds window) {
    const auto deadline = Clock::now() + window;
    while (!closed_ && Clock::now() < deadline) read_for(5ms);
    return closed_;
  }

 private:
  /// Reads for `window`, and past it while bytes are waiting: a fast port (the real-time one's
  /// 196 kB/s) queues more than one read takes, and what is left would pass for fresh.
  void read_for(std::chrono::milliseconds window) {
    const auto deadline = Clock::now() + window;
    while (true) {
      const bool past_deadline = Clock::now() >= deadline;
      if (!transport::wait_readable(socket_.fd(), past_deadline ? 0ms : std::min(window, 5ms))) {
        if (past_deadline) return;
        continue;
      }
      std::array<std::uint8_t, 16384> bytes{};
      const ssize_t n = ::recv(socket_.fd(), bytes.data(), bytes.size(), 0);
      if (n <= 0) {
        closed_ = n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK);
        return;
      }
      splitter_.append(ByteView(bytes.data(), static_cast<std::size_t>(n)));
      while (true) {
        auto packet = splitter_.next();
        ASSERT_TRUE(packet) << packet.error().message;
        if (!packet.value()) break;
        packets_.push_back(std::move(*packet.value()));
      }
    }
  }

  ReportKind kind_;
  transport::Socket socket_;
  ReportSplitter splitter_;
  std::vector<Bytes> packets_;
  bool closed_ = false;
};

/// Runs the simulator with `arguments` to its end; its exit status (stdout and stderr to /dev/null).
int run_to_exit(const std::vector<std::string>& arguments) {
  return testing::run_to_exit(XarmSimProcess::executable(), arguments);
}

class XarmSimTest : public ::testing::Test {
 protected:
  void SetUp() override { start({"--quiet"}); }

  void start(std::vector<std::string> arguments) {
    client_.reset();
    sim_.reset();
    sim_ = std::make_unique<XarmSimProcess>(std::move(arguments));
    client_ = std::make_unique<Connection>(sim_->port());
  }

  json control(const json& request) {
    json reply = sim_->control(request);
    EXPECT_TRUE(reply.value("ok", false)) << request.dump() << " -> " << reply.dump();
    return reply;
  }
  json state() { return control({{"op", "state"}}); }
  int arm_state() {
    const auto data = client_->request(plain_request(Register::kGetState)).data;
    return data.empty() ? -1 : data[0];
  }
  ErrorWarning codes() {
    const auto codes = parse_err_code(client_->request(plain_request(Register::kGetErrCode)).data);
    return codes ? codes.value() : ErrorWarning{.error = -1, .warning = -1};
  }
  JointValues joints() {
    const auto joints = parse_joints(client_->request(plain_request(Register::kGetJointPos)).data);
    return joints ? joints.value() : JointValues{};
  }
  Pose tcp_pose() {
    const auto pose = parse_pose(client_->request(plain_request(Register::kGetTcpPose)).data);
    return pose ? pose.value() : Pose{};
  }
  /// The standard bring-up: motion_en(8, 1) → state 5 → set_state(0) → state 2.
  void bring_up() {
    EXPECT_EQ(client_->request(motion_enable_request(8, true)).status_byte, kNotReady);
    EXPECT_EQ(arm_state(), kStateReset);
    EXPECT_EQ(client_->request(set_state_request(kStateStart)).status_byte, 0);
    EXPECT_EQ(arm_state(), kStateSleeping);
  }
  void enter_mode(int mode) {
    bring_up();
    client_->request(set_mode_request(mode));
    client_->request(set_state_request(kStateStart));
    ASSERT_EQ(arm_state(), kStateSleeping);
  }
  /// Polls get_state until it is `wanted`; how long it took, or nullopt after `timeout`.
  std::optional<double> wait_for_state(int wanted, std::chrono::milliseconds timeout = 3000ms) {
    const auto start = Clock::now();
    while (Clock::now() - start < timeout) {
      if (arm_state() == wanted) return std::chrono::duration<double>(Clock::now() - start).count();
      std::this_thread::sleep_for(5ms);
    }
    return std::nullopt;
  }
  void set_joints(const JointValues& joints, std::size_t dof = 6) {
    control({{"op", "set_joints"},
             {"joints_rad", std::vector<double>(joints.begin(), joints.begin() + static_cast<std::ptrdiff_t>(dof))}});
  }

  std::unique_ptr<XarmSimProcess> sim_;
  std::unique_ptr<Connection> client_;
};

void expect_joints_near(const JointValues& actual, const JointValues& expected, double tolerance) {
  for (std::size_t j = 0; j < kMaxDof; ++j) EXPECT_NEAR(actual[j], expected[j], tolerance) << "joint " << j + 1;
}

/// How far `point` is from the line through `a` and `b`.
double distance_from_line(const Pose& point, const Pose& a, const Pose& b) {
  std::array<double, 3> along{};
  std::array<double, 3> from_a{};
  double length = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    along[i] = b.position_m[i] - a.position_m[i];
    from_a[i] = point.position_m[i] - a.position_m[i];
    length += along[i] * along[i];
  }
  length = std::sqrt(length);
  double projected = 0;
  for (std::size_t i = 0; i < 3; ++i) projected += from_a[i] * along[i] / length;
  double squared = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const double off = from_a[i] - projected * along[i] / length;
    squared += off * off;
  }
  return std::sqrt(squared);
}

void expect_position_near(const Pose& actual, const Pose& expected, double tolerance_m) {
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(actual.position_m[i], expected.position_m[i], tolerance_m) << i;
}

// --- power-on and bring-up ----------------------------------------------------------------------

TEST_F(XarmSimTest, PowersOnDisabledStoppedAtZero) {
  const json s = state();
  EXPECT_EQ(s["state"], kStateStopped);
  EXPECT_EQ(s["mode"], kModePosition);
  EXPECT_EQ(s["error"], 0);
  EXPECT_EQ(s["warning"], 0);
  EXPECT_EQ(s["enabled"], json(std::vector<bool>(6, false)));
  EXPECT_EQ(s["brakes_released"], json(std::vector<bool>(6, false)));
  const Reply reply = client_->request(plain_request(Register::kGetState));
  EXPECT_EQ(reply.status_byte, kNotReady) << "disabled and stopped";
  EXPECT_EQ(reply.data, Bytes{kStateStopped});
  expect_joints_near(joints(), JointValues{}, 0);
  EXPECT_EQ(client_->request(set_state_request(kStateStart)).status_byte, kNotReady);
  EXPECT_EQ(arm_state(), kStateStopped) << "set_state(0) needs the motors enabled";
}

TEST_F(XarmSimTest, BringUpEnablesResetsThenSleeps) {
  bring_up();
  const json s = state();
  EXPECT_EQ(s["enabled"], json(std::vector<bool>(6, true)));
  EXPECT_EQ(s["brakes_released"], json(std::vector<bool>(6, true)));
  EXPECT_EQ(s["commands"]["motion_en"], 1);
  EXPECT_EQ(s["commands"]["set_state"], 1);
}

TEST_F(XarmSimTest, EveryRegisterAnswersWithItsDataShape) {
  bring_up();
  const auto version = parse_version(client_->request(plain_request(Register::kGetVersion)).data);
  ASSERT_TRUE(version) << version.error().message;
  EXPECT_EQ(version.value().axes, 6);
  EXPECT_EQ(version.value().type, 6);
  EXPECT_EQ(version.value().firmware, "2.3.0");
  // The controller's format: the version carries the series, the SN register the whole numbers;
  // the SDK reads digits 2-5 as a number.
  EXPECT_EQ(version.value().robot_sn, "XI1303");
  EXPECT_EQ(version.value().control_box_sn, "AC1303");
  const Reply serials = client_->request(plain_request(Register::kGetRobotSn));
  EXPECT_EQ(serials.data.size(), 40U);
  const auto parsed_serials = parse_robot_sn(serials.data);
  ASSERT_TRUE(parsed_serials) << parsed_serials.error().message;
  EXPECT_EQ(parsed_serials.value().robot_sn, "XI1303RBTDSIM1");
  EXPECT_EQ(parsed_serials.value().control_box_sn, "AC1303RBTDSIM1");
  const std::vector<std::pair<Request, std::size_t>> shapes = {
      {plain_request(Register::kGetState), 1},
      {plain_request(Register::kGetCmdnum), 2},
      {plain_request(Register::kGetErrCode), 2},
      {plain_request(Register::kGetTcpPose), 24},
      {plain_request(Register::kGetJointPos), 28},
      {get_fk_request(JointValues{}), 24},
      {is_joint_limit_request(JointValues{}), 1},
      {plain_request(Register::kServoGetDbmsg), 16},
      {plain_request(Register::kFeedbackCheck), 0},
      {plain_request(Register::kCleanWar), 0},
      {plain_request(Register::kSaveConf), 0},
      {plain_request(Register::kCleanConf), 0},
      {set_tcp_maxacc_request(2.0), 2},
      {set_joint_maxacc_request(10.0), 2},
      {set_tcp_jerk_request(10.0), 2},
      {set_joint_jerk_request(100.0), 2},
      {raw_request(Register::kGetJointPos, {3}), 84},
      {raw_request(Register::kSetFeedbackType, {0}), 0},
      {plain_request(Register::kGetReducedMode), 1},
      {set_reduced_mode_request(false), 0},
  };
  for (const auto& [request, size] : shapes) {
    const Reply reply = client_->request(request);
    EXPECT_EQ(reply.data.size(), size) << register_name(request.reg);
    EXPECT_EQ(reply.status_byte, 0) << register_name(request.reg);
  }
  const Reply keep_alive = client_->request(plain_request(Register::kGetState), kProtocolKeepAlive);
  EXPECT_EQ(keep_alive.protocol, kProtocolKeepAlive) << "protocol id 3 is echoed";
  EXPECT_EQ(keep_alive.data, Bytes{kStateSleeping});
}

TEST_F(XarmSimTest, ForwardAndInverseKinematicsAgree) {
  const auto pose = parse_pose(client_->request(get_fk_request(posture())).data);
  ASSERT_TRUE(pose);
  ByteWriter ik;
  for (const double mm : pose.value().position_m) ik.f32_le(mm * 1000);
  for (const double rad : pose.value().rpy_rad) ik.f32_le(rad);
  const Reply solved = client_->request(raw_request(Register::kGetIk, ik.take()));
  ASSERT_EQ(solved.status_byte & kInvalid, 0);
  const auto joints = parse_joints(solved.data);
  ASSERT_TRUE(joints);
  const auto again = parse_pose(client_->request(get_fk_request(joints.value())).data);
  ASSERT_TRUE(again);
  expect_position_near(again.value(), pose.value(), 1e-4);
  EXPECT_EQ(client_->request(is_joint_limit_request(posture())).data, Bytes{0});
  EXPECT_EQ(client_->request(is_joint_limit_request(JointValues{0, 3.0, 0, 0, 0, 0, 0})).data, Bytes{1});
}

// --- planned motion -----------------------------------------------------------------------------

TEST_F(XarmSimTest, MoveJointQueuesRunsAtItsSpeedAndDrains) {
  bring_up();
  // 0.6 rad at 1 rad/s with 10 rad/s²: 0.1 s ramps, 0.5 s cruise — 0.7 s.
  const JointValues target{0.6, -0.1, -0.2, 0.3, 0.2, -0.1, 0};
  const auto start = Clock::now();
  const Reply first = client_->request(move_joint_request(joint_move(target)));
  EXPECT_EQ(first.status_byte, 0);
  EXPECT_EQ(cmdnum(first.data), 1);
  const Reply second = client_->request(sleep_instruction_request(0.2));
  EXPECT_EQ(cmdnum(second.data), 2);
  EXPECT_EQ(arm_state(), kStateMoving);
  EXPECT_EQ(state()["cmdnum"], 2);
  const auto took = wait_for_state(kStateSleeping);
  ASSERT_TRUE(took);
  const double elapsed_s = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_GT(elapsed_s, 0.85) << "0.7 s of motion and 0.2 s of sleep";
  EXPECT_LT(elapsed_s, 2.0);
  expect_joints_near(joints(), target, kWireRad);
  EXPECT_EQ(cmdnum(client_->request(plain_request(Register::kGetCmdnum)).data), 0);
}

TEST_F(XarmSimTest, MoveJointIsSynchronisedAndTrapezoidal) {
  bring_up();
  client_->request(move_joint_request(joint_move({0.8, 0.4, 0, 0, 0, 0, 0}, 1.0, 4.0)));  // 0.25 s ramps, 1.05 s
  std::this_thread::sleep_for(525ms);                                                     // half way
  const JointValues half = joints();
  EXPECT_NEAR(half[0], 0.4, 0.1);
  EXPECT_NEAR(half[1] / half[0], 0.5, 0.01) << "both joints arrive together";
  ASSERT_TRUE(wait_for_state(kStateSleeping));
  expect_joints_near(joints(), {0.8, 0.4, 0, 0, 0, 0, 0}, kWireRad);
}

TEST_F(XarmSimTest, MoveLineKeepsTheTcpOnAStraightLine) {
  set_joints(posture());
  bring_up();
  const Pose start = tcp_pose();
  Pose goal = start;
  goal.position_m[1] += 0.08;
  goal.position_m[2] -= 0.06;
  const LineMove move{.pose = goal, .speed_m_s = 0.2, .acc_m_s2 = 2.0, .mvtime_s = 0, .blend_radius_m = 0};
  const Reply reply = client_->request(move_line_request(move));
  ASSERT_EQ(reply.status_byte, 0);
  // Along the way the TCP stays on the segment (within 1 mm).
  int samples = 0;
  while (arm_state() == kStateMoving) {
    EXPECT_LT(distance_from_line(tcp_pose(), start, goal), 1e-3);
    ++samples;
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_GT(samples, 10) << "0.1 m at 0.2 m/s takes 0.6 s";
  const Pose end = tcp_pose();
  expect_position_near(end, goal, 1e-4);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(std::remainder(end.rpy_rad[i] - goal.rpy_rad[i], 2 * std::numbers::pi), 0, 1e-3);
}

TEST_F(XarmSimTest, AnUnreachableLineIsRefusedWithWarning14) {
  set_joints(posture());
  bring_up();
  Pose far = tcp_pose();
  far.position_m[0] = 2.0;
  const Reply reply = client_->request(move_line_request(LineMove{.pose = far}));
  EXPECT_EQ(reply.status_byte, kInvalid | kWarning);
  EXPECT_EQ(cmdnum(reply.data), 0) << "nothing queued";
  EXPECT_EQ(codes().warning, 14);
  EXPECT_EQ(arm_state(), kStateSleeping);
}

TEST_F(XarmSimTest, PauseHoldsOnThePathAndStartResumes) {
  bring_up();
  client_->request(move_joint_request(joint_move({0.8, 0, 0, 0, 0, 0, 0})));  // 0.9 s
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(client_->request(set_state_request(kStatePaused)).status_byte, 0);
  EXPECT_EQ(arm_state(), kStatePaused);
  std::this_thread::sleep_for(200ms);  // it brakes within 0.1 s
  const double held = joints()[0];
  std::this_thread::sleep_for(150ms);
  EXPECT_DOUBLE_EQ(joints()[0], held) << "paused";
  EXPECT_GT(held, 0.1);
  EXPECT_LT(held, 0.7);
  EXPECT_EQ(state()["cmdnum"], 1) << "the cache is kept";
  client_->request(set_state_request(kStateStart));
  EXPECT_EQ(arm_state(), kStateMoving);
  ASSERT_TRUE(wait_for_state(kStateSleeping));
  EXPECT_NEAR(joints()[0], 0.8, kWireRad);
}

TEST_F(XarmSimTest, StopHaltsAndClearsTheCache) {
  bring_up();
  client_->request(move_joint_request(joint_move({0.8, 0, 0, 0, 0, 0, 0})));
  client_->request(move_joint_request(joint_move({0, 0, 0, 0, 0, 0, 0})));
  std::this_thread::sleep_for(300ms);
  const Reply stop = client_->request(set_state_request(kStateStopped));
  EXPECT_EQ(stop.status_byte, kNotReady);
  EXPECT_EQ(arm_state(), kStateStopped);
  const double held = joints()[0];
  std::this_thread::sleep_for(100ms);
  EXPECT_DOUBLE_EQ(joints()[0], held);
  EXPECT_EQ(cmdnum(client_->request(plain_request(Register::kGetCmdnum)).data), 0);
  const Reply refused = client_->request(move_joint_request(joint_move({})));
  EXPECT_EQ(refused.status_byte, kNotReady) << "STOPPED until set_state(0)";
  EXPECT_EQ(cmdnum(refused.data), 0);
  client_->request(set_state_request(kStateStart));
  EXPECT_EQ(arm_state(), kStateSleeping);
}

TEST_F(XarmSimTest, DeceleratedStopBrakesOnThePathThenStops) {
  bring_up();
  client_->request(move_joint_request(joint_move({1.0, 0, 0, 0, 0, 0, 0}, 1.0, 2.0)));  // 0.5 s ramps
  std::this_thread::sleep_for(600ms);  // cruising at 1 rad/s: braking takes 0.5 s and 0.25 rad
  const double at_command = joints()[0];
  client_->request(set_state_request(kStateSlowStop));
  const auto took = wait_for_state(kStateStopped);
  ASSERT_TRUE(took);
  EXPECT_GT(*took, 0.3);
  const double stopped = joints()[0];
  EXPECT_GT(stopped - at_command, 0.15);
  EXPECT_LT(stopped, 0.99) << "it stopped short of the target";
  EXPECT_EQ(state()["cmdnum"], 0);
}

TEST_F(XarmSimTest, SleepInstructionDelaysTheNextMove) {
  bring_up();
  client_->request(sleep_instruction_request(0.4));
  client_->request(move_joint_request(joint_move({0.1, 0, 0, 0, 0, 0, 0})));
  std::this_thread::sleep_for(250ms);
  EXPECT_DOUBLE_EQ(joints()[0], 0) << "still sleeping";
  ASSERT_TRUE(wait_for_state(kStateSleeping));
  EXPECT_NEAR(joints()[0], 0.1, kWireRad);
}

TEST_F(XarmSimTest, MoveGohomeReturnsToZero) {
  set_joints(posture());
  bring_up();
  client_->request(move_gohome_request(joint_move({}, 2.0, 20.0)));
  ASSERT_TRUE(wait_for_state(kStateSleeping));
  expect_joints_near(joints(), JointValues{}, kWireRad);
}

TEST_F(XarmSimTest, QueuedMovesNeedPositionModeAndAReadyArm) {
  const Reply disabled = client_->request(move_joint_request(joint_move({0.1, 0, 0, 0, 0, 0, 0})));
  EXPECT_EQ(disabled.status_byte, kNotReady);
  enter_mode(kModeServo);
  const Reply servo_mode = client_->request(move_joint_request(joint_move({0.1, 0, 0, 0, 0, 0, 0})));
  EXPECT_EQ(servo_mode.status_byte, kNotReady) << "ready, but not in mode 0";
  EXPECT_EQ(cmdnum(servo_mode.data), 0);
  EXPECT_EQ(state()["cmdnum"], 0);
}

TEST_F(XarmSimTest, AJointTargetBeyondItsLimitLatchesC23AndStops) {
  bring_up();
  const Reply reply = client_->request(move_joint_request(joint_move({0, 3.0, 0, 0, 0, 0, 0})));
  EXPECT_EQ(reply.status_byte, kError | kNotReady);
  EXPECT_EQ(codes().error, 23);
  EXPECT_EQ(arm_state(), kStateStopped);
  EXPECT_EQ(client_->request(plain_request(Register::kCleanErr)).status_byte, kNotReady);
  EXPECT_EQ(codes().error, 0);
  EXPECT_EQ(arm_state(), kStateReset);
  client_->request(set_state_request(kStateStart));
  EXPECT_EQ(arm_state(), kStateSleeping) << "C23 leaves the motors enabled";
}

TEST_F(XarmSimTest, TheCacheHolds1024CommandsThenWarns11) {
  bring_up();
  for (int i = 0; i < 1025; ++i) client_->send(sleep_instruction_request(10));
  for (int i = 0; i < 1024; ++i) {
    const auto reply = client_->next_reply();
    ASSERT_TRUE(reply);
    ASSERT_EQ(reply->status_byte, 0) << i;
  }
  const auto full = client_->next_reply();
  ASSERT_TRUE(full);
  EXPECT_EQ(full->status_byte, kInvalid | kWarning);
  EXPECT_EQ(cmdnum(full->data), 1024);
  EXPECT_EQ(codes().warning, 11);
}

TEST_F(XarmSimTest, ResetRegistersPutTheArmInState5) {
  const std::vector<Request> resets = {
      motion_enable_request(8, true),
      plain_request(Register::kCleanErr),
      set_brake_request(8, true),
      set_mode_request(kModePosition),
      set_tcp_offset_request(Pose{}),
      raw_request(Register::kSetCollisionSensitivity, {3}),
      raw_request(Register::kSetTeachSensitivity, {3}),
  };
  bring_up();
  for (const Request& request : resets) {
    client_->request(move_joint_request(joint_move({0.5, 0, 0, 0, 0, 0, 0})));
    const Reply reply = client_->request(request);
    EXPECT_EQ(reply.status_byte, kNotReady) << register_name(request.reg);
    EXPECT_EQ(arm_state(), kStateReset) << register_name(request.reg);
    EXPECT_EQ(state()["cmdnum"], 0) << register_name(request.reg);
    client_->request(set_state_request(kStateStart));
    EXPECT_EQ(arm_state(), kStateSleeping) << register_name(request.reg);
  }
}

TEST_F(XarmSimTest, MotionFeedbackTellsStartAndFinish) {
  bring_up();
  client_->request(raw_request(Register::kSetFeedbackType, {3}));
  const std::uint16_t id = client_->send(move_joint_request(joint_move({0.1, 0, 0, 0, 0, 0, 0}, 2.0, 20.0)));
  const auto started = client_->next_feedback();
  ASSERT_TRUE(started);
  EXPECT_EQ(started->type, 1);
  EXPECT_EQ(started->transaction_id, id);
  EXPECT_EQ(started->command_reg, reg_of(Register::kMoveJoint));
  const auto finished = client_->next_feedback();
  ASSERT_TRUE(finished);
  EXPECT_EQ(finished->type, 2);
  EXPECT_EQ(finished->code, 0);
  EXPECT_EQ(finished->task_id, started->task_id);
  ASSERT_TRUE(client_->next_reply());  // the move's own reply came first

  client_->request(move_joint_request(joint_move({0.5, 0, 0, 0, 0, 0, 0})));
  client_->request(set_state_request(kStateStopped));
  std::optional<MotionFeedback> discarded;
  while (auto feedback = client_->next_feedback(300ms)) discarded = feedback;
  ASSERT_TRUE(discarded);
  EXPECT_EQ(discarded->type, 2);
  EXPECT_EQ(discarded->code, 2) << "discarded";

  Connection other(sim_->port());
  client_->request(set_state_request(kStateStart));
  client_->request(move_joint_request(joint_move({0, 0, 0, 0, 0, 0, 0}, 2.0, 20.0)));
  EXPECT_FALSE(other.next_feedback(300ms)) << "feedback goes to the connection that asked for it";
  EXPECT_GE(state()["feedback_frames_sent"], 4);
}

TEST_F(XarmSimTest, AMoveKeepsTheFeedbackTypeItWasSentWith) {
  bring_up();
  // The SDK's wait: ask for "finished", send the move, restore the mask at once, wait for the frame.
  client_->request(set_feedback_type_request(kFeedbackMotionFinish));
  const Reply queued = client_->request(move_joint_request(joint_move({0.1, 0, 0, 0, 0, 0, 0}, 2.0, 20.0)));
  client_->request(set_feedback_type_request(0));
  const auto finished = client_->next_feedback();
  ASSERT_TRUE(finished) << "the move's finish frame, though the mask is 0 again";
  EXPECT_EQ(finished->type, 2);
  EXPECT_EQ(finished->transaction_id, queued.transaction_id);
  client_->request(move_joint_request(joint_move({0, 0, 0, 0, 0, 0, 0}, 2.0, 20.0)));
  EXPECT_FALSE(client_->next_feedback(500ms)) << "a move sent with mask 0 has no frame";
}

TEST_F(XarmSimTest, ReducedModeIsAFlagToSetAndRead) {
  EXPECT_EQ(client_->request(plain_request(Register::kGetReducedMode)).data, Bytes{0});
  EXPECT_EQ(client_->request(set_reduced_mode_request(true)).status_byte & 0x08, 0);
  EXPECT_EQ(client_->request(plain_request(Register::kGetReducedMode)).data, Bytes{1});
  EXPECT_TRUE(state()["reduced_mode"].get<bool>());
  const Reply refused = client_->request(raw_request(Register::kSetReducedMode, {2}));
  EXPECT_TRUE(refused.status.invalid);
  EXPECT_EQ(state()["warning"], 12);
  EXPECT_EQ(client_->request(plain_request(Register::kGetReducedMode)).data, Bytes{1});
}

// --- the xArm gripper ---------------------------------------------------------------------------

TEST_F(XarmSimTest, TheGripperStopsOnAnObjectAndSaysItGripsIt) {
  const auto write = [&](GripperRegister reg, std::vector<std::uint16_t> values) {
    const Reply reply =
        client_->request(tool_modbus_write_request(kGripperId, static_cast<std::uint16_t>(reg), values));
    ASSERT_TRUE(parse_tool_modbus_write_reply(reply.data, kGripperId, static_cast<std::uint16_t>(reg),
                                              static_cast<std::uint16_t>(values.size())));
  };
  const auto read = [&](GripperRegister reg, std::uint16_t count) {
    const Reply reply = client_->request(tool_modbus_read_request(kGripperId, static_cast<std::uint16_t>(reg), count));
    return parse_tool_modbus_read_reply(reply.data, kGripperId, count).value();
  };
  const auto settled_status = [&] {
    for (int i = 0; i < 400 && read(GripperRegister::kStatus, 1)[0] == kGripperMoving; ++i) {
      std::this_thread::sleep_for(10ms);
    }
    return read(GripperRegister::kStatus, 1)[0];
  };
  write(GripperRegister::kEnable, {1});
  write(GripperRegister::kSpeed, {5000});
  write(GripperRegister::kTargetPosition, {0, 600});
  EXPECT_EQ(settled_status(), kGripperStopped);
  control({{"op", "gripper_object"}, {"width_pulses", 300}});
  write(GripperRegister::kTargetPosition, {0, 0});
  EXPECT_EQ(settled_status(), kGripperGripping);
  EXPECT_EQ(read(GripperRegister::kPosition, 2), (std::vector<std::uint16_t>{0, 300}));
  EXPECT_EQ(read(GripperRegister::kTargetPosition, 2), (std::vector<std::uint16_t>{0, 0}));
  write(GripperRegister::kTargetPosition, {0, 500});
  EXPECT_EQ(settled_status(), kGripperStopped) << "opening lets go of the object";
  EXPECT_EQ(read(GripperRegister::kPosition, 2), (std::vector<std::uint16_t>{0, 500}));
}

// --- servo mode ---------------------------------------------------------------------------------

TEST_F(XarmSimTest, ServoJFollowsTheNewestTarget) {
  enter_mode(kModeServo);
  const auto start = Clock::now();
  for (int k = 1; k <= 30; ++k) {
    std::this_thread::sleep_until(start + k * 10ms);
    const Reply reply = client_->request(servo_j_request({0.01 * k, 0, 0, 0, 0, 0, 0}));
    ASSERT_EQ(reply.status_byte, 0);
    ASSERT_TRUE(reply.data.empty());
  }
  std::this_thread::sleep_for(50ms);
  EXPECT_NEAR(joints()[0], 0.3, kWireRad);
  const json servo = state()["servo"];
  EXPECT_EQ(servo["frames"], 30);
  EXPECT_EQ(servo["ignored"], 0);
  EXPECT_GT(servo["max_interval_us"], 5000);
  EXPECT_NEAR(servo["last_target_rad"][0].get<double>(), 0.3, kWireRad);
  EXPECT_EQ(codes().error, 0);
}

TEST_F(XarmSimTest, ServoJStepsAtMost180DegreesPerSecond) {
  enter_mode(kModeServo);
  client_->request(servo_j_request({1.0, 0, 0, 0, 0, 0, 0}));  // a stream's first target: no previous to judge by
  std::this_thread::sleep_for(100ms);
  const double after_100ms = joints()[0];
  EXPECT_GT(after_100ms, 0.15);
  EXPECT_LT(after_100ms, 0.55) << "π rad/s at most";
  EXPECT_EQ(arm_state(), kStateMoving);
  ASSERT_TRUE(wait_for_state(kStateSleeping));
  EXPECT_NEAR(joints()[0], 1.0, kWireRad);
}

TEST_F(XarmSimTest, AServoStepTooFastLatchesC24) {
  enter_mode(kModeServo);
  client_->request(servo_j_request({0.01, 0, 0, 0, 0, 0, 0}));
  const Reply reply = client_->request(servo_j_request({0.3, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(reply.status_byte, kError | kNotReady);
  EXPECT_EQ(codes().error, 24);
  EXPECT_EQ(arm_state(), kStateStopped);
  EXPECT_EQ(state()["servo"]["frames"], 1);
}

TEST_F(XarmSimTest, ServoJOutsideServoModeIsIgnored) {
  bring_up();
  const Reply reply = client_->request(servo_j_request({0.2, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(reply.status_byte, 0) << "the live status: ready, in mode 0";
  std::this_thread::sleep_for(50ms);
  EXPECT_DOUBLE_EQ(joints()[0], 0);
  client_->request(motion_enable_request(8, false));
  EXPECT_EQ(client_->request(servo_j_request({0.2, 0, 0, 0, 0, 0, 0})).status_byte, kNotReady);
  const json servo = state()["servo"];
  EXPECT_EQ(servo["ignored"], 2);
  EXPECT_EQ(servo["frames"], 0);
}

// --- errors and warnings ------------------------------------------------------------------------

TEST_F(XarmSimTest, ErrorsAndWarningsShowInEveryReplysStatus) {
  bring_up();
  control({{"op", "warning"}, {"code", 15}});
  EXPECT_EQ(client_->request(plain_request(Register::kGetState)).status_byte, kWarning);
  control({{"op", "error"}, {"code", 31}});
  EXPECT_EQ(client_->request(plain_request(Register::kGetState)).status_byte, kError | kWarning | kNotReady);
  EXPECT_EQ(codes().error, 31);
  EXPECT_EQ(codes().warning, 15);
  EXPECT_EQ(arm_state(), kStateStopped);
  client_->request(plain_request(Register::kCleanWar));
  client_->request(plain_request(Register::kCleanErr));
  EXPECT_EQ(client_->request(plain_request(Register::kGetState)).status_byte, kNotReady) << "state 5 after clean_err";
  client_->request(set_state_request(kStateStart));
  EXPECT_EQ(client_->request(plain_request(Register::kGetState)).status_byte, 0);
}

TEST_F(XarmSimTest, AHeldEstopCannotBeCleaned) {
  bring_up();
  control({{"op", "estop"}, {"pressed", true}});
  EXPECT_EQ(codes().error, 1);
  EXPECT_EQ(state()["enabled"], json(std::vector<bool>(6, false))) << "an e-stop cuts the motors";
  EXPECT_EQ(client_->request(plain_request(Register::kCleanErr)).status_byte, kError | kNotReady);
  EXPECT_EQ(codes().error, 1) << "still pressed";
  control({{"op", "estop"}, {"pressed", false}});
  client_->request(plain_request(Register::kCleanErr));
  EXPECT_EQ(codes().error, 0);
  client_->request(set_state_request(kStateStart));
  EXPECT_EQ(arm_state(), kStateReset) << "the motors need motion_en again";
  bring_up();
}

TEST_F(XarmSimTest, AServoErrorShowsInDbmsgAndDisablesTheMotors) {
  bring_up();
  control({{"op", "servo_error"}, {"joint", 2}, {"code", 11}});
  EXPECT_EQ(codes().error, 12);
  const auto servos = parse_servo_dbmsg(client_->request(plain_request(Register::kServoGetDbmsg)).data);
  ASSERT_TRUE(servos);
  EXPECT_EQ(servos.value()[1].state, 1);
  EXPECT_EQ(servos.value()[1].error, 11);
  EXPECT_EQ(servos.value()[0].state, 0);
  EXPECT_EQ(state()["enabled"], json(std::vector<bool>(6, false)));
  client_->request(plain_request(Register::kCleanErr));
  const auto cleared = parse_servo_dbmsg(client_->request(plain_request(Register::kServoGetDbmsg)).data);
  ASSERT_TRUE(cleared);
  EXPECT_EQ(cleared.value()[1].error, 0);
}

TEST_F(XarmSimTest, BadRequestsSetInvalidAndAWarning) {
  bring_up();
  const Reply short_enable = client_->request(raw_request(Register::kMotionEnable, {8}));
  EXPECT_EQ(short_enable.status_byte, kInvalid | kWarning);
  EXPECT_EQ(codes().warning, 12);
  client_->request(plain_request(Register::kCleanWar));
  EXPECT_EQ(client_->request(motion_enable_request(7, true)).status_byte, kInvalid | kWarning)
      << "an xArm 6 has no joint 7";
  EXPECT_EQ(client_->request(set_state_request(7)).status_byte, kInvalid | kWarning);
  EXPECT_EQ(client_->request(set_mode_request(kModeJointVelocity)).status_byte, kInvalid | kWarning)
      << "mode 4 is not emulated";
  EXPECT_EQ(arm_state(), kStateSleeping) << "a refused set_mode resets nothing";
  client_->request(plain_request(Register::kCleanWar));

  const Reply unknown = client_->request(Request{.reg = 99, .params = {}});
  EXPECT_EQ(unknown.status_byte, kInvalid | kWarning);
  EXPECT_EQ(codes().warning, 13);
  const Reply circle = client_->request(raw_request(Register::kMoveCircle, Bytes(64, 0)));
  EXPECT_EQ(circle.status_byte, kInvalid | kWarning);
  EXPECT_EQ(circle.data.size(), 2U) << "a motion register still answers with the count";
  const Reply joint_tau = client_->request(Request{.reg = 55, .params = {}});
  EXPECT_EQ(joint_tau.status_byte, kInvalid | kWarning);
  EXPECT_EQ(joint_tau.data, Bytes(28, 0))
      << "an unemulated getter answers its 7 floats, zero, so a client reads the status";
  client_->request(plain_request(Register::kCleanWar));

  const Reply modbus = client_->request(plain_request(Register::kGetState), 0);
  EXPECT_EQ(modbus.status_byte, kInvalid) << "protocol id 0 is not the private protocol";
  EXPECT_TRUE(modbus.data.empty());
  EXPECT_EQ(modbus.protocol, 0);
}

TEST_F(XarmSimTest, MotionSettersAreRefusedWhileStopped) {
  EXPECT_EQ(client_->request(set_tcp_maxacc_request(1.0)).status_byte, kInvalid | kNotReady);
  EXPECT_EQ(codes().warning, 0);
  bring_up();
  EXPECT_EQ(client_->request(set_tcp_maxacc_request(1.0)).status_byte, 0);
  EXPECT_EQ(client_->request(set_joint_maxacc_request(5.0)).status_byte, 0);
  EXPECT_EQ(client_->request(set_joint_maxacc_request(500.0)).status_byte, kInvalid | kWarning) << "out of range";
  const json limits = state()["limits"];
  EXPECT_NEAR(limits["tcp_max_acc_m_s2"].get<double>(), 1.0, 1e-6);
  EXPECT_NEAR(limits["joint_max_acc_rad_s2"].get<double>(), 5.0, 1e-6);
  // The joint max acc caps a move's: 0.5 rad at 1 rad/s with 5 (not 50) rad/s² takes 0.7 s.
  const auto start = Clock::now();
  client_->request(move_joint_request(joint_move({0.5, 0, 0, 0, 0, 0, 0}, 1.0, 20.0)));
  ASSERT_TRUE(wait_for_state(kStateSleeping));
  EXPECT_GT(std::chrono::duration<double>(Clock::now() - start).count(), 0.6);
}

// --- configuration ------------------------------------------------------------------------------

TEST_F(XarmSimTest, TheTcpOffsetMovesThePose) {
  const Pose flange = tcp_pose();
  Pose offset;
  offset.position_m = {0, 0, 0.1};
  EXPECT_EQ(client_->request(set_tcp_offset_request(offset)).status_byte, kNotReady);
  EXPECT_EQ(arm_state(), kStateReset);
  const Pose tool = tcp_pose();
  EXPECT_NEAR(tool.position_m[2], flange.position_m[2] - 0.1, 1e-6) << "the flange points down at zero";
  const auto fk = parse_pose(client_->request(get_fk_request(JointValues{})).data);
  ASSERT_TRUE(fk);
  EXPECT_NEAR(fk.value().position_m[2], tool.position_m[2], 1e-6);
  EXPECT_NEAR(state()["tcp_offset"][2].get<double>(), 0.1, 1e-6);
}

TEST_F(XarmSimTest, CleanConfRestoresDefaultsAndSaveConfRemembers) {
  Pose offset;
  offset.position_m = {0, 0, 0.05};
  client_->request(set_tcp_offset_request(offset));
  client_->request(plain_request(Register::kSaveConf));
  EXPECT_EQ(state()["saved_conf"], true);
  client_->request(plain_request(Register::kCleanConf));
  const json s = state();
  EXPECT_EQ(s["saved_conf"], false);
  EXPECT_EQ(s["tcp_offset"], json({0, 0, 0, 0, 0, 0}));
}

// --- other models -------------------------------------------------------------------------------

TEST(XarmSimModels, ASevenJointArmHoldsJoint3ForLines) {
  XarmSimProcess sim({"--quiet", "--model", "xarm7", "--firmware", "2.4.0"});
  Connection client(sim.port());
  const auto version = parse_version(client.request(plain_request(Register::kGetVersion)).data);
  ASSERT_TRUE(version);
  EXPECT_EQ(version.value().axes, 7);
  EXPECT_EQ(version.value().type, 7);
  EXPECT_EQ(version.value().firmware, "2.4.0");
  const JointValues start{0, -0.2, 0.3, 0.9, 0, 1.1, 0};
  ASSERT_TRUE(
      sim.control({{"op", "set_joints"}, {"joints_rad", std::vector<double>(start.begin(), start.end())}})["ok"]);
  client.request(motion_enable_request(8, true));
  client.request(set_state_request(kStateStart));
  auto pose = parse_pose(client.request(plain_request(Register::kGetTcpPose)).data);
  ASSERT_TRUE(pose);
  Pose goal = pose.value();
  goal.position_m[2] += 0.05;
  ASSERT_EQ(client.request(move_line_request(LineMove{.pose = goal, .speed_m_s = 0.25, .acc_m_s2 = 5})).status_byte, 0);
  std::this_thread::sleep_for(600ms);
  const auto end = parse_pose(client.request(plain_request(Register::kGetTcpPose)).data);
  ASSERT_TRUE(end);
  expect_position_near(end.value(), goal, 1e-4);
  const auto joints = parse_joints(client.request(plain_request(Register::kGetJointPos)).data);
  ASSERT_TRUE(joints);
  EXPECT_NEAR(joints.value()[2], 0.3, kWireRad) << "joint 3 held";
}

TEST(XarmSimModels, AFiveJointArmRefusesLinesWithWarning14) {
  XarmSimProcess sim({"--quiet", "--model", "xarm5"});
  Connection client(sim.port());
  client.request(motion_enable_request(8, true));
  client.request(set_state_request(kStateStart));
  const Reply reply = client.request(move_line_request(LineMove{}));
  EXPECT_EQ(reply.status_byte, kInvalid | kWarning);
  EXPECT_EQ(parse_err_code(client.request(plain_request(Register::kGetErrCode)).data).value().warning, 14);
  EXPECT_EQ(sim.control({{"op", "state"}})["dof"], 5);
}

// --- reports ------------------------------------------------------------------------------------

TEST(XarmSimReports, EachPortSendsItsPacketsAtItsRate) {
  const std::uint16_t normal = XarmSimProcess::free_port();
  const std::uint16_t realtime = XarmSimProcess::free_port();
  XarmSimProcess sim(
      {"--quiet", "--normal-report-port", std::to_string(normal), "--realtime-report-port", std::to_string(realtime)});
  struct Expectation {
    std::uint16_t port;
    ReportKind kind;
    std::size_t size;
    std::size_t low;  // packets in 0.5 s, loosely
    std::size_t high;
  };
  for (const Expectation& port : {Expectation{sim.report_port(), ReportKind::kReal, 87, 25, 60},
                                  Expectation{normal, ReportKind::kNormal, 145, 2, 4},
                                  Expectation{realtime, ReportKind::kRealtime, 784, 60, 135}}) {
    ReportReader reader(port.port, port.kind);
    const auto packets = reader.packets_for(500ms);
    EXPECT_GE(packets.size(), port.low) << report_kind_name(port.kind);
    EXPECT_LE(packets.size(), port.high) << report_kind_name(port.kind);
    for (const Bytes& packet : packets) {
      ASSERT_EQ(packet.size(), port.size) << report_kind_name(port.kind);
      ASSERT_TRUE(parse_report(packet, port.kind)) << report_kind_name(port.kind);
    }
  }
  EXPECT_GT(sim.control({{"op", "state"}})["reports_sent"], 120);
}

TEST(XarmSimReports, ReportFtMakesRealReports135Bytes) {
  XarmSimProcess sim({"--quiet", "--report-ft"});
  ReportReader reader(sim.report_port(), ReportKind::kReal);
  const auto packets = reader.packets_for(100ms);
  ASSERT_FALSE(packets.empty());
  EXPECT_EQ(packets.front().size(), 135U);
}

TEST_F(XarmSimTest, ReportsCarryTheArmsState) {
  const std::uint16_t normal = XarmSimProcess::free_port();
  start({"--quiet", "--normal-report-port", std::to_string(normal)});
  set_joints(posture());
  bring_up();
  control({{"op", "warning"}, {"code", 15}});
  ReportReader real(sim_->report_port(), ReportKind::kReal);
  const auto report = real.fresh();
  ASSERT_TRUE(report);
  EXPECT_EQ(report->state, kStateSleeping);
  EXPECT_EQ(report->mode, kModePosition);
  expect_joints_near(report->position_rad, posture(), kWireRad);
  expect_position_near(report->tcp_pose, tcp_pose(), 1e-6);
  ReportReader codes_port(normal, ReportKind::kNormal);
  const auto with_codes = codes_port.fresh(500ms);
  ASSERT_TRUE(with_codes);
  EXPECT_EQ(with_codes->enable_mask, 0x3F);
  EXPECT_EQ(with_codes->brake_mask, 0x3F);
  EXPECT_EQ(with_codes->warning_code, 15);
  EXPECT_EQ(with_codes->error_code, 0);
  EXPECT_EQ(state()["report_clients"], 2);
}

TEST_F(XarmSimTest, NormalReportsCarryTheSettings) {
  const std::uint16_t normal = XarmSimProcess::free_port();
  start({"--quiet", "--normal-report-port", std::to_string(normal)});
  const Pose offset{.position_m = {0.01, -0.02, 0.1}, .rpy_rad = {0, 0, 0.5}};
  client_->request(set_tcp_offset_request(offset));
  const Bytes load = ByteWriter().f32_le(1.5).f32_le(0).f32_le(10).f32_le(40).take();  // kg, then mm
  EXPECT_EQ(client_->request(raw_request(Register::kSetLoadParam, load)).status_byte & kInvalid, 0);
  EXPECT_EQ(client_->request(raw_request(Register::kSetCollisionSensitivity, {5})).status_byte & kInvalid, 0);
  ReportReader reader(normal, ReportKind::kNormal);
  const auto report = reader.fresh(1000ms);  // 5 Hz
  ASSERT_TRUE(report);
  ASSERT_TRUE(report->has_settings);
  expect_position_near(report->tcp_offset, offset, 1e-6);
  EXPECT_NEAR(report->tcp_offset.rpy_rad[2], 0.5, kWireRad);
  EXPECT_EQ(report->payload_kg, 1.5);
  EXPECT_NEAR(report->payload_centre_m[1], 0.01, 1e-6);
  EXPECT_NEAR(report->payload_centre_m[2], 0.04, 1e-6);
  EXPECT_EQ(report->collision_sensitivity, 5);
  EXPECT_EQ(report->teach_sensitivity, 3) << "the default";
  ASSERT_TRUE(report->has_gravity_direction);
  EXPECT_EQ(report->gravity_direction, (std::array<double, 3>{0, 0, -1}));
}

TEST_F(XarmSimTest, RealtimeReportsCarryTheServoTarget) {
  const std::uint16_t realtime = XarmSimProcess::free_port();
  start({"--quiet", "--realtime-report-port", std::to_string(realtime)});
  enter_mode(kModeServo);
  ReportReader reader(realtime, ReportKind::kRealtime);
  const JointValues target{1.0, -0.8, 0, 0, 0, 0, 0};
  client_->request(servo_j_request(target));  // a stream's first target: the joints go there at π rad/s
  const auto moving = reader.fresh();
  ASSERT_TRUE(moving);
  ASSERT_TRUE(moving->has_targets);
  expect_joints_near(moving->target_position_rad, target, kWireRad);
  EXPECT_LT(moving->position_rad[0], 0.9) << "still on its way: 1 rad takes 0.32 s";
  EXPECT_NEAR(moving->target_velocity_rad_s[0], std::numbers::pi, kWireRad);
  EXPECT_NEAR(moving->target_velocity_rad_s[1], -std::numbers::pi, kWireRad);
  EXPECT_EQ(moving->target_velocity_rad_s[2], 0) << "already on its target";
  ASSERT_TRUE(wait_for_state(kStateSleeping));
  const auto arrived = reader.fresh();
  ASSERT_TRUE(arrived);
  expect_joints_near(arrived->target_position_rad, target, kWireRad);
  expect_joints_near(arrived->position_rad, target, kWireRad);
  expect_joints_near(arrived->target_velocity_rad_s, JointValues{}, 0);
}

TEST_F(XarmSimTest, RealtimeReportsCarryThePlannedProfile) {
  const std::uint16_t realtime = XarmSimProcess::free_port();
  start({"--quiet", "--realtime-report-port", std::to_string(realtime)});
  bring_up();
  ReportReader reader(realtime, ReportKind::kRealtime);
  // 0.6 rad at 1 rad/s with 10 rad/s²: cruising from 0.1 s to 0.6 s.
  const JointValues target{0.6, -0.3, 0, 0, 0, 0, 0};
  ASSERT_EQ(client_->request(move_joint_request(joint_move(target))).status_byte, 0);
  std::this_thread::sleep_for(300ms);
  const auto cruising = reader.fresh();
  ASSERT_TRUE(cruising);
  ASSERT_TRUE(cruising->has_targets);
  EXPECT_NEAR(cruising->target_velocity_rad_s[0], 1.0, 1e-6);
  EXPECT_NEAR(cruising->target_velocity_rad_s[1], -0.5, 1e-6) << "synchronised: half the way at half the speed";
  expect_joints_near(cruising->target_position_rad, cruising->position_rad, 0);
  ASSERT_TRUE(wait_for_state(kStateSleeping));
  const auto done = reader.fresh();
  ASSERT_TRUE(done);
  expect_joints_near(done->target_position_rad, target, kWireRad);
  expect_joints_near(done->target_velocity_rad_s, JointValues{}, 0);
}

// --- the control channel ------------------------------------------------------------------------

TEST_F(XarmSimTest, DropRepliesSwallowsTheNextN) {
  control({{"op", "drop_replies"}, {"count", 2}});
  client_->send(plain_request(Register::kGetState));
  client_->send(plain_request(Register::kGetState));
  EXPECT_FALSE(client_->next_reply(200ms));
  EXPECT_EQ(arm_state(), kStateStopped) << "the third is answered";
  const json s = state();
  EXPECT_EQ(s["replies_dropped"], 2);
  EXPECT_EQ(s["replies_sent"], 1);
}

TEST_F(XarmSimTest, AGarbageFrameIsAWellFormedReplyNobodyAskedFor) {
  client_->request(plain_request(Register::kGetState));
  EXPECT_EQ(control({{"op", "garbage"}, {"kind", "frame"}})["clients"], 1);
  const auto garbage = client_->next_reply();
  ASSERT_TRUE(garbage);
  EXPECT_EQ(garbage->reg, 0x63);
  EXPECT_NE(garbage->transaction_id, 1);
  EXPECT_EQ(arm_state(), kStateStopped) << "the stream still makes sense";
  EXPECT_EQ(state()["garbage_sent"], 1);
}

TEST_F(XarmSimTest, GarbageBytesBreakTheFramingUntilReconnected) {
  control({{"op", "garbage"}, {"kind", "bytes"}});
  EXPECT_FALSE(client_->next_reply(200ms));
  EXPECT_TRUE(client_->broken());
  client_ = std::make_unique<Connection>(sim_->port());
  EXPECT_EQ(arm_state(), kStateStopped);
}

TEST_F(XarmSimTest, DisconnectClosesEveryClientAndKeepsListening) {
  ReportReader reports(sim_->report_port(), ReportKind::kReal);
  client_->request(plain_request(Register::kGetState));
  EXPECT_EQ(state()["report_clients"], 1);
  EXPECT_EQ(control({{"op", "disconnect"}})["closed"], 2);
  EXPECT_TRUE(client_->closed_within(500ms));
  EXPECT_TRUE(reports.closed_within(500ms));
  client_ = std::make_unique<Connection>(sim_->port());
  EXPECT_EQ(arm_state(), kStateStopped);
}

TEST_F(XarmSimTest, SilenceStopsTheReportsButNotTheCommands) {
  ReportReader reports(sim_->report_port(), ReportKind::kReal);
  control({{"op", "silence"}, {"on", true}});
  EXPECT_TRUE(reports.packets_for(200ms).empty());
  EXPECT_EQ(arm_state(), kStateStopped);
  control({{"op", "silence"}, {"on", false}});
  EXPECT_GT(reports.packets_for(200ms).size(), 10U);
}

TEST_F(XarmSimTest, AFramingErrorClosesOnlyThatClient) {
  Connection other(sim_->port());
  client_->send_raw(Bytes{0, 1, 0, 2, 0, 0, 13});  // a length field of 0
  EXPECT_TRUE(client_->closed_within(500ms));
  EXPECT_EQ(other.request(plain_request(Register::kGetState)).data, Bytes{kStateStopped});
}

TEST_F(XarmSimTest, RepliesGoToTheClientThatAsked) {
  Connection other(sim_->port());
  other.send(plain_request(Register::kGetCmdnum));
  client_->send(plain_request(Register::kGetErrCode));
  EXPECT_EQ(other.next_reply().value_or(Reply{}).reg, reg_of(Register::kGetCmdnum));
  EXPECT_EQ(client_->next_reply().value_or(Reply{}).reg, reg_of(Register::kGetErrCode));
  EXPECT_FALSE(other.next_reply(100ms));
  EXPECT_EQ(state()["command_clients"], 2);
}

TEST_F(XarmSimTest, ControlRefusesBadRequestsWithReasons) {
  const auto expect_error = [this](const json& request, const std::string& part) {
    const json reply = sim_->control(request);
    EXPECT_FALSE(reply.value("ok", true)) << request.dump();
    EXPECT_NE(reply.value("error", "").find(part), std::string::npos) << request.dump() << " -> " << reply.dump();
  };
  expect_error({{"op", "fly"}}, "unknown op \"fly\"");
  expect_error({{"op", "error"}, {"code", 256}}, "\"code\"");
  expect_error({{"op", "servo_error"}, {"joint", 7}, {"code", 1}}, "\"joint\"");
  expect_error({{"op", "estop"}, {"pressed", 1}}, "true or false");
  expect_error({{"op", "garbage"}, {"kind", "noise"}}, "\"frame\"");
  expect_error({{"op", "set_joints"}, {"joints_rad", {0, 0}}}, "6 numbers (rad)");
  expect_error({{"op", "set_joints"}, {"joints_rad", {0, 3, 0, 0, 0, 0}}}, "joint 2");
  expect_error({{"op", "state"}, {"verbose", true}}, "does not take \"verbose\"");
  EXPECT_TRUE(state()["ok"].get<bool>()) << "still serving";
}

// --- the process --------------------------------------------------------------------------------

TEST_F(XarmSimTest, RestartedItListensOnTheSamePorts) {
  const std::uint16_t port = sim_->port();
  const std::uint16_t report_port = sim_->report_port();
  sim_->kill_hard();
  EXPECT_TRUE(client_->closed_within(500ms));
  sim_->restart();
  EXPECT_EQ(sim_->port(), port);
  client_ = std::make_unique<Connection>(port);
  EXPECT_EQ(arm_state(), kStateStopped);
  ReportReader reports(report_port, ReportKind::kReal);
  EXPECT_FALSE(reports.packets_for(100ms).empty());
}

TEST_F(XarmSimTest, SigtermEndsItCleanly) { EXPECT_EQ(sim_->terminate(), 0); }

TEST(XarmSimCommandLine, BadOptionsExitWith2) {
  const std::string port = std::to_string(XarmSimProcess::free_port());
  EXPECT_EQ(run_to_exit({}), 2) << "no --port";
  EXPECT_EQ(run_to_exit({"--port", "70000"}), 2);
  EXPECT_EQ(run_to_exit({"--port", port, "--report-port", "0"}), 2);
  EXPECT_EQ(run_to_exit({"--port", port, "--model", "xarm9"}), 2);
  EXPECT_EQ(run_to_exit({"--port", port, "--firmware", "two"}), 2);
  EXPECT_EQ(run_to_exit({"--port", port, "--bogus"}), 2);
}

TEST(XarmSimCommandLine, APortInUseExitsWith2) {
  const XarmSimProcess first({"--quiet"});
  EXPECT_EQ(run_to_exit({"--port", std::to_string(first.port()), "--quiet"}), 2);
  EXPECT_EQ(run_to_exit({"--port", std::to_string(XarmSimProcess::free_port()), "--report-port",
                         std::to_string(first.report_port()), "--quiet"}),
            2);
  EXPECT_TRUE(first.control({{"op", "state"}})["ok"].get<bool>()) << "the first one is unharmed";
}

}  // namespace
}  // namespace robotd::xarm
