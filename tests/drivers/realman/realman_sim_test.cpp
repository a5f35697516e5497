// robotd-realman-sim as a client sees it: a real process on 127.0.0.1, spoken to over real TCP
// (CR LF–framed JSON) and listened to over real UDP, and steered through its control channel.
#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <sys/socket.h>
#include <thread>
#include <tuple>
#include <unistd.h>
#include <vector>

#include <gtest/gtest.h>

#include "codec/realman_codec.hpp"
#include "realman_sim_process.hpp"
#include "robotd/transport/ip_socket.hpp"

namespace robotd::realman {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;
using testing::RealmanSimProcess;
using Clock = std::chrono::steady_clock;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr auto kReplyTimeout = 1000ms;

/// A well-conditioned RM65 posture (flange at x −410 mm, z 337 mm, pointing down), in rad.
std::vector<double> posture_rad() { return {0, 30 * kDeg, 60 * kDeg, 0, 60 * kDeg, 0}; }

std::vector<std::int64_t> millidegrees(const std::vector<double>& degrees) {
  std::vector<std::int64_t> out;
  out.reserve(degrees.size());
  for (const double d : degrees) out.push_back(std::llround(d * 1000));
  return out;
}

json movej(const std::vector<double>& degrees, int v = 50, int connect = 0) {
  return {{"command", "movej"}, {"joint", millidegrees(degrees)}, {"v", v}, {"r", 0}, {"trajectory_connect", connect}};
}

json canfd(const std::vector<double>& degrees, bool follow = true) {
  return {{"command", "movej_canfd"}, {"joint", millidegrees(degrees)}, {"follow", follow}};
}

json plain(const char* command) { return {{"command", command}}; }

/// A controller client: one TCP connection, its replies and events kept apart.
class Connection {
 public:
  explicit Connection(std::uint16_t port) {
    auto connected = transport::connect_tcp(transport::Endpoint{"127.0.0.1", port}, 1000ms);
    if (!connected) throw std::runtime_error(connected.error().message);
    socket_ = std::move(connected).value();
  }

  void send(const json& message) { send_raw(frame(message)); }
  void send_raw(std::string_view bytes) {
    std::size_t offset = 0;
    while (offset < bytes.size()) {
      std::size_t sent = 0;
      ASSERT_NE(transport::send_some(socket_.fd(), bytes.substr(offset), sent), transport::SendResult::kClosed);
      offset += sent;
      if (sent == 0) std::this_thread::sleep_for(1ms);
    }
  }
  /// The next message that is not an event, or nullopt after `timeout`.
  std::optional<json> next_reply(std::chrono::milliseconds timeout = kReplyTimeout) {
    return next_of(replies_, timeout);
  }
  /// The next current_trajectory_state event, or nullopt after `timeout`.
  std::optional<json> next_event(std::chrono::milliseconds timeout = kReplyTimeout) {
    return next_of(events_, timeout);
  }
  json request(const json& message) {
    send(message);
    auto reply = next_reply();
    return reply ? *reply : json{{"no_reply_to", message}};
  }
  /// Reads for `window`; true if the peer closed meanwhile.
  bool closed_within(std::chrono::milliseconds window) {
    const auto deadline = Clock::now() + window;
    while (!closed_ && Clock::now() < deadline) read_some(left_until(deadline));
    return closed_;
  }
  const std::vector<std::string>& unreadable() const { return unreadable_; }

 private:
  static std::chrono::milliseconds left_until(Clock::time_point deadline) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    return std::clamp(left, 0ms, 5ms);
  }
  std::optional<json> next_of(std::vector<json>& queue, std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    do {  // reads at least once: a zero timeout takes what is waiting
      if (!queue.empty() || closed_) break;
      read_some(left_until(deadline));
    } while (Clock::now() < deadline);
    if (queue.empty()) return std::nullopt;
    json message = queue.front();
    queue.erase(queue.begin());
    return message;
  }
  void read_some(std::chrono::milliseconds wait) {
    if (!transport::wait_readable(socket_.fd(), wait)) return;
    std::array<char, 8192> bytes{};
    const ssize_t n = ::recv(socket_.fd(), bytes.data(), bytes.size(), 0);
    if (n <= 0) {
      closed_ = n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK);
      return;
    }
    lines_.append(std::string_view(bytes.data(), static_cast<std::size_t>(n)));
    while (auto line = lines_.next()) {
      json message = json::parse(*line, nullptr, false);
      if (message.is_discarded()) {
        unreadable_.push_back(*line);
      } else if (message.contains("state") && message["state"] == "current_trajectory_state") {
        events_.push_back(message);
      } else {
        replies_.push_back(message);
      }
    }
  }

  transport::Socket socket_;
  LineSplitter lines_;
  std::vector<json> replies_;
  std::vector<json> events_;
  std::vector<std::string> unreadable_;
  bool closed_ = false;
};

/// Where the UDP push is told to go: a socket on 127.0.0.1.
class PushReceiver {
 public:
  PushReceiver() {
    auto bound = transport::bind_udp(transport::Endpoint{"127.0.0.1", 0});
    if (!bound) throw std::runtime_error(bound.error().message);
    socket_ = std::move(bound).value();
    port_ = transport::local_endpoint(socket_.fd()).value().port;
  }
  std::uint16_t port() const { return port_; }

  /// The next datagram as received (with its CR LF), or nullopt after `timeout`.
  std::optional<std::string> next(std::chrono::milliseconds timeout = 500ms) {
    const auto deadline = Clock::now() + timeout;
    while (true) {  // tries at least once: a zero timeout takes what is waiting
      std::array<char, 65536> bytes{};
      const ssize_t n = ::recv(socket_.fd(), bytes.data(), bytes.size(), 0);
      if (n >= 0) return std::string(bytes.data(), static_cast<std::size_t>(n));
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
      if (left <= 0ms) return std::nullopt;
      transport::wait_readable(socket_.fd(), std::min(left, 5ms));
    }
  }
  std::optional<json> next_json(std::chrono::milliseconds timeout = 500ms) {
    auto datagram = next(timeout);
    if (!datagram) return std::nullopt;
    return json::parse(*datagram, nullptr, false);
  }
  /// The next datagram sent after now (what waited is dropped).
  std::optional<json> fresh_json() {
    drop_waiting();
    return next_json();
  }
  /// Datagrams that arrive within `window` (after dropping what waited).
  int count_for(std::chrono::milliseconds window) {
    drop_waiting();
    int count = 0;
    const auto deadline = Clock::now() + window;
    while (Clock::now() < deadline) {
      if (next(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()))) ++count;
    }
    return count;
  }

 private:
  void drop_waiting() {
    while (next(0ms)) {
    }
  }

  transport::Socket socket_;
  std::uint16_t port_ = 0;
};

/// Runs the simulator with `arguments` to its end; its exit status (stdout and stderr to /dev/null).
int run_to_exit(const std::vector<std::string>& arguments) {
  return testing::run_to_exit(RealmanSimProcess::executable(), arguments);
}

class RealmanSimTest : public ::testing::Test {
 protected:
  void SetUp() override { start({"--quiet"}); }

  void start(std::vector<std::string> arguments) {
    client_.reset();
    sim_.reset();
    sim_ = std::make_unique<RealmanSimProcess>(std::move(arguments));
    client_ = std::make_unique<Connection>(sim_->port());
  }

  json control(const json& request) {
    json reply = sim_->control(request);
    EXPECT_TRUE(reply.value("ok", false)) << request.dump() << " -> " << reply.dump();
    return reply;
  }
  json state() { return control({{"op", "state"}}); }
  std::vector<double> joints_deg() {
    const json joints = state()["joints_rad"];
    std::vector<double> out;
    for (const auto& rad : joints) out.push_back(rad.get<double>() / kDeg);
    return out;
  }
  void teleport(const std::vector<double>& rad) { control({{"op", "set_joints"}, {"joints_rad", rad}}); }
  /// Sends the push to `receiver` with these custom fields.
  void push_to(const PushReceiver& receiver, const json& custom = json::object(), int cycle = 1) {
    const json reply = client_->request({{"command", "set_realtime_push"},
                                         {"cycle", cycle},
                                         {"enable", true},
                                         {"port", receiver.port()},
                                         {"ip", "127.0.0.1"},
                                         {"custom", custom}});
    ASSERT_EQ(reply, json({{"command", "set_realtime_push"}, {"state", true}})) << reply.dump();
  }
  /// Streams `count` movej_canfd frames one `period` apart, `at(k)` giving frame k's joints (°).
  void stream(int count, std::chrono::microseconds period, const std::function<std::vector<double>(int)>& at,
              bool follow = true) {
    const auto first = Clock::now();
    for (int k = 0; k < count; ++k) {
      std::this_thread::sleep_until(first + k * period);
      client_->send(canfd(at(k), follow));
    }
  }

  std::unique_ptr<RealmanSimProcess> sim_;
  std::unique_ptr<Connection> client_;
};

// --- the exchange -------------------------------------------------------------------------------

TEST_F(RealmanSimTest, QueriesAnswerWithTheirStateKey) {
  const std::vector<std::pair<const char*, const char*>> queries = {
      {"get_current_arm_state", "current_arm_state"},
      {"get_joint_degree", "joint_degree"},
      {"get_arm_all_state", "arm_all_state"},
      {"get_controller_state", "controller_state"},
      {"get_current_joint_temperature", "current_joint_temperature"},
      {"get_current_joint_current", "current_joint_current"},
      {"get_current_joint_voltage", "current_joint_voltage"},
      {"get_joint_en_state", "joint_en_state"},
      {"get_joint_err_flag", "joint_err_flag"},
      {"get_arm_plan_num", "arm_plan_num"},
      {"get_arm_power_state", "arm_power_state"},
      {"get_init_pose", "arm_init_pose"},
      {"get_joint_min_pos", "joint_min_pos"},
      {"get_joint_max_pos", "joint_max_pos"},
      {"get_arm_current_trajectory", "arm_current_trajectory"},
  };
  for (const auto& [command, key] : queries) {
    const json reply = client_->request(plain(command));
    EXPECT_EQ(reply.value("state", ""), key) << command << " -> " << reply.dump();
  }
  EXPECT_EQ(client_->request(plain("get_gripper_state")).value("command", ""), "get_gripper_state");
  EXPECT_EQ(client_->request(plain("get_realtime_push")).value("command", ""), "get_realtime_push");
  EXPECT_EQ(client_->request(plain("get_arm_software_info")).value("command", ""), "arm_software_info");
}

// The vendor SDK (RM_API2 v1.1.5) asks these at rm_create_robot_arm and gives up on the first it
// cannot parse; the shapes and units are what it parsed and what its setters send
// (tests/conformance/realman).
TEST_F(RealmanSimTest, TheQueriesTheVendorSdkAsksAtConnectAreAnswered) {
  EXPECT_EQ(client_->request(plain("get_current_work_frame")),
            json({{"state", "current_work_frame"}, {"frame_name", "Base"}, {"pose", {0, 0, 0, 0, 0, 0}}}));
  EXPECT_EQ(client_->request(plain("get_current_tool_frame")), json({{"state", "current_tool_frame"},
                                                                     {"tool_name", "Arm_Tip"},
                                                                     {"pose", {0, 0, 0, 0, 0, 0}},
                                                                     {"payload", 0},
                                                                     {"position", {0, 0, 0}}}));
  EXPECT_EQ(client_->request(plain("get_install_pose")), json({{"state", "install_pose"}, {"pose", {0, 0, 0}}}));
  // 180 °/s = 30 rpm and 720 °/s² = 120 rpm/s, in 0.001 rpm (/s).
  EXPECT_EQ(client_->request(plain("get_joint_max_speed")),
            json({{"state", "joint_max_speed"}, {"joint_speed", {30000, 30000, 30000, 30000, 30000, 30000}}}));
  EXPECT_EQ(client_->request(plain("get_joint_max_acc")),
            json({{"state", "joint_max_acc"}, {"joint_acc", {120000, 120000, 120000, 120000, 120000, 120000}}}));
  // RM65's table: [alpha 0.001°, a µm, d µm, offset 0.001°] per joint.
  EXPECT_EQ(client_->request(plain("get_DH_data")), json({{"command", "get_DH_data"},
                                                          {"joint_1", {0, 0, 240500, 0}},
                                                          {"joint_2", {90000, 0, 0, 90000}},
                                                          {"joint_3", {0, 256000, 0, 90000}},
                                                          {"joint_4", {90000, 0, 210000, 0}},
                                                          {"joint_5", {-90000, 0, 0, 0}},
                                                          {"joint_6", {90000, 0, 144000, 0}}}));
}

TEST_F(RealmanSimTest, SettersAnswerWithTheirResultKey) {
  const std::vector<std::tuple<json, const char*, const char*>> setters = {
      {{{"command", "set_arm_power"}, {"arm_power", 1}}, "set_arm_power", "arm_power"},
      {{{"command", "set_joint_en_state"}, {"joint_en_state", {2, 1}}}, "set_joint_en_state", "joint_en_state"},
      {{{"command", "set_joint_clear_err"}, {"joint_clear_err", 3}}, "set_joint_clear_err", "joint_clear_err"},
      {plain("clear_system_err"), "clear_system_err", "clear_state"},
      {{{"command", "set_init_pose"}, {"init_pose", {0, 1000, 2000, 0, 0, 0}}}, "set_init_pose", "init_pose"},
      {plain("set_arm_stop"), "set_arm_stop", "arm_stop"},
      {plain("set_arm_slow_stop"), "set_arm_slow_stop", "arm_slow_stop"},
      {plain("set_arm_pause"), "set_arm_pause", "arm_pause"},
      {plain("set_arm_continue"), "set_arm_continue", "arm_continue"},
      {{{"command", "set_gripper_route"}, {"min", 70}, {"max", 500}}, "set_gripper_route", "state"},
      {{{"command", "set_gripper_release"}, {"speed", 500}, {"block", false}}, "set_gripper", "state"},
      {{{"command", "set_hand_speed"}, {"hand_speed", 500}}, "set_hand_speed", "set_state"},
      {{{"command", "set_hand_force"}, {"hand_force", 500}}, "set_hand_force", "set_state"},
      {{{"command", "set_realtime_push"}, {"cycle", 2}}, "set_realtime_push", "state"},
  };
  for (const auto& [request, command, key] : setters) {
    const json reply = client_->request(request);
    EXPECT_EQ(reply, json({{"command", command}, {key, true}})) << request.dump() << " -> " << reply.dump();
  }
  EXPECT_EQ(client_->request(movej({0, 0, 0, 0, 0, 0})), json({{"command", "movej"}, {"receive_state", true}}));
}

TEST_F(RealmanSimTest, PrettyMultiLineJsonIsOneMessage) {
  client_->send_raw("{\n\t\"command\": \"get_joint_degree\"\n}\r\n");
  const auto reply = client_->next_reply();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["state"], "joint_degree");
  EXPECT_FALSE(client_->next_reply(100ms)) << "one message, one reply";
}

TEST_F(RealmanSimTest, SeveralMessagesInOneSegmentAreEachAnswered) {
  client_->send_raw(frame(plain("get_joint_degree")) + frame(plain("get_arm_power_state")) +
                    frame(plain("get_joint_en_state")));
  EXPECT_EQ(client_->next_reply().value_or(json())["state"], "joint_degree");
  EXPECT_EQ(client_->next_reply().value_or(json())["state"], "arm_power_state");
  EXPECT_EQ(client_->next_reply().value_or(json())["state"], "joint_en_state");
}

TEST_F(RealmanSimTest, AMessageSplitAcrossSegmentsIsAnsweredOnceComplete) {
  const std::string message = frame(plain("get_joint_degree"));
  client_->send_raw(message.substr(0, 10));
  EXPECT_FALSE(client_->next_reply(100ms));
  client_->send_raw(message.substr(10, message.size() - 11));  // all but the LF
  EXPECT_FALSE(client_->next_reply(100ms)) << "a CR alone does not end it";
  client_->send_raw("\n");
  EXPECT_EQ(client_->next_reply().value_or(json())["state"], "joint_degree");
}

TEST_F(RealmanSimTest, AnUnknownCommandIsNamedInTheError) {
  EXPECT_EQ(client_->request(plain("fly")), json({{"command", "fly"}, {"error", "unknown command 'fly'"}}));
}

TEST_F(RealmanSimTest, MalformedJsonGetsAnErrorWithAnEmptyCommand) {
  client_->send_raw("{\"command\": \"get_joint_degree\"\r\n");
  const auto reply = client_->next_reply();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["command"], "");
  EXPECT_EQ((*reply)["error"].get<std::string>().rfind("malformed JSON", 0), 0U) << reply->dump();
  EXPECT_EQ(client_->request(plain("get_joint_degree"))["state"], "joint_degree") << "the next one is answered";
  EXPECT_EQ(state()["malformed"], 1);
}

TEST_F(RealmanSimTest, BadParametersGetTheNormalReplyFalseWithAReason) {
  const json short_joints = client_->request({{"command", "movej"}, {"joint", {0, 0}}, {"v", 20}});
  EXPECT_EQ(short_joints["receive_state"], false);
  EXPECT_EQ(short_joints["error"], "\"joint\" must be 6 integers (0.001°), got [0,0]");
  const json no_speed = client_->request({{"command", "movej"}, {"joint", {0, 0, 0, 0, 0, 0}}});
  EXPECT_EQ(no_speed["error"], "missing \"v\" (an integer 1 … 100)");
  const json slow = client_->request({{"command", "set_gripper_pick"}, {"speed", 0}, {"force", 200}});
  EXPECT_EQ(
      slow,
      json({{"command", "set_gripper"}, {"state", false}, {"error", "\"speed\" must be an integer 1 … 1000, got 0"}}));
  const json typed = client_->request({{"command", "set_arm_power"}, {"arm_power", "on"}});
  EXPECT_EQ(typed["arm_power"], false);
  EXPECT_NE(typed["error"].get<std::string>().find("true or false"), std::string::npos) << typed.dump();
}

TEST_F(RealmanSimTest, RepliesGoToTheClientThatAsked) {
  Connection other(sim_->port());
  other.send(plain("get_arm_power_state"));
  client_->send(plain("get_joint_degree"));
  EXPECT_EQ(other.next_reply().value_or(json())["state"], "arm_power_state");
  EXPECT_EQ(client_->next_reply().value_or(json())["state"], "joint_degree");
  EXPECT_FALSE(other.next_reply(100ms));
  EXPECT_EQ(state()["clients"], 2);
}

// --- planned motion -----------------------------------------------------------------------------

TEST_F(RealmanSimTest, MovejEndsWithAnEventAfterItsPlannedTime) {
  // 90° at v 50 (90 °/s): 1 s at full speed plus one 0.25 s ramp.
  const auto start = Clock::now();
  ASSERT_EQ(client_->request(movej({90, 0, 0, 0, 0, 0}, 50))["receive_state"], true);
  EXPECT_EQ(state()["status"], "move_J");
  const auto event = client_->next_event(3000ms);
  const double took_s = std::chrono::duration<double>(Clock::now() - start).count();
  ASSERT_TRUE(event);
  EXPECT_EQ(*event, json({{"state", "current_trajectory_state"},
                          {"trajectory_state", true},
                          {"device", 0},
                          {"trajectory_connect", 0}}));
  EXPECT_NEAR(took_s, 1.25, 0.1);
  EXPECT_NEAR(joints_deg()[0], 90, 1e-6);
  EXPECT_EQ(client_->request(plain("get_joint_degree"))["joint"], json({90000, 0, 0, 0, 0, 0}));
}

TEST_F(RealmanSimTest, TheEventGoesOnlyToTheClientThatStartedTheMotion) {
  Connection other(sim_->port());
  ASSERT_EQ(client_->request(movej({5, 0, 0, 0, 0, 0}, 100))["receive_state"], true);
  EXPECT_TRUE(client_->next_event());
  EXPECT_FALSE(other.next_event(200ms));
}

TEST_F(RealmanSimTest, ATargetBeyondALimitIsRefusedWithoutLatchingAnError) {
  const json reply = client_->request(movej({0, 0, 140, 0, 0, 0}));
  EXPECT_EQ(reply["receive_state"], false);
  EXPECT_EQ(reply["error"],
            "joint 3 target 140.000° is outside -135.000° … 135.000° (0x1002 target angle beyond joint limit)");
  EXPECT_EQ(client_->request(plain("get_current_arm_state"))["arm_state"]["err"], json::array({0}));
  EXPECT_EQ(client_->request(movej({0, 0, 10, 0, 0, 0}, 100))["receive_state"], true) << "nothing to clear";
}

TEST_F(RealmanSimTest, ConnectedSegmentsWaitForOneWithoutConnectThenRunInOrder) {
  ASSERT_EQ(client_->request(movej({10, 0, 0, 0, 0, 0}, 100, 1))["receive_state"], true);
  ASSERT_EQ(client_->request(movej({10, 10, 0, 0, 0, 0}, 100, 1))["receive_state"], true);
  std::this_thread::sleep_for(150ms);
  EXPECT_EQ(joints_deg(), std::vector<double>(6, 0.0)) << "held until a segment without connect";
  EXPECT_EQ(state()["trajectory"]["held"], 2);
  ASSERT_EQ(client_->request(movej({10, 10, 10, 0, 0, 0}, 100, 0))["receive_state"], true);
  std::vector<int> connects;
  for (int i = 0; i < 3; ++i) {
    const auto event = client_->next_event(2000ms);
    ASSERT_TRUE(event) << "segment " << i;
    EXPECT_EQ((*event)["trajectory_state"], true);
    connects.push_back((*event)["trajectory_connect"].get<int>());
  }
  EXPECT_EQ(connects, (std::vector<int>{1, 1, 0}));
  const auto joints = joints_deg();
  EXPECT_NEAR(joints[0], 10, 1e-6);
  EXPECT_NEAR(joints[1], 10, 1e-6);
  EXPECT_NEAR(joints[2], 10, 1e-6);
}

TEST_F(RealmanSimTest, AMotionWhileOneRunsIsRefused) {
  ASSERT_EQ(client_->request(movej({60, 0, 0, 0, 0, 0}, 50))["receive_state"], true);
  const json second = client_->request(movej({0, 0, 0, 0, 0, 0}, 50));
  EXPECT_EQ(second["receive_state"], false);
  EXPECT_NE(second["error"].get<std::string>().find("a trajectory is in progress"), std::string::npos);
}

TEST_F(RealmanSimTest, StopEndsTheMotionAtOnceWithAFalseEvent) {
  ASSERT_EQ(client_->request(movej({90, 0, 0, 0, 0, 0}, 50))["receive_state"], true);
  std::this_thread::sleep_for(400ms);
  EXPECT_EQ(client_->request(plain("set_arm_stop")), json({{"command", "set_arm_stop"}, {"arm_stop", true}}));
  const auto event = client_->next_event();
  ASSERT_TRUE(event);
  EXPECT_EQ((*event)["trajectory_state"], false);
  const double stopped_at = joints_deg()[0];
  EXPECT_GT(stopped_at, 5);
  EXPECT_LT(stopped_at, 60);
  std::this_thread::sleep_for(100ms);
  EXPECT_EQ(joints_deg()[0], stopped_at);
  EXPECT_EQ(state()["status"], "stop");
}

TEST_F(RealmanSimTest, SlowStopDeceleratesOnThePathThenReportsFalse) {
  ASSERT_EQ(client_->request(movej({90, 0, 0, 0, 0, 0}, 50))["receive_state"], true);
  std::this_thread::sleep_for(500ms);  // cruising at 90 °/s
  const auto asked = Clock::now();
  const double at_request = joints_deg()[0];
  EXPECT_EQ(client_->request(plain("set_arm_slow_stop"))["arm_slow_stop"], true);
  const auto event = client_->next_event();
  ASSERT_TRUE(event);
  EXPECT_EQ((*event)["trajectory_state"], false);
  EXPECT_NEAR(std::chrono::duration<double>(Clock::now() - asked).count(), 0.2, 0.08) << "200 ms to a halt";
  EXPECT_NEAR(joints_deg()[0] - at_request, 9, 2.5) << "half of 90 °/s over 0.2 s";
}

TEST_F(RealmanSimTest, PauseHoldsOnThePathAndContinueFinishes) {
  ASSERT_EQ(client_->request(movej({40, 0, 0, 0, 0, 0}, 50))["receive_state"], true);
  std::this_thread::sleep_for(200ms);
  EXPECT_EQ(client_->request(plain("set_arm_pause"))["arm_pause"], true);
  std::this_thread::sleep_for(300ms);
  const double held = joints_deg()[0];
  EXPECT_EQ(state()["status"], "pause");
  std::this_thread::sleep_for(200ms);
  EXPECT_EQ(joints_deg()[0], held);
  EXPECT_FALSE(client_->next_event(10ms));
  EXPECT_EQ(client_->request(plain("set_arm_continue"))["arm_continue"], true);
  const auto event = client_->next_event(2000ms);
  ASSERT_TRUE(event);
  EXPECT_EQ((*event)["trajectory_state"], true);
  EXPECT_NEAR(joints_deg()[0], 40, 1e-6);
}

TEST_F(RealmanSimTest, DeletingTrajectoriesNeedsAPause) {
  const json early = client_->request(plain("set_arm_delete_trajectory"));
  EXPECT_EQ(early["arm_delete_trajectory"], false);
  EXPECT_EQ(early["error"], "only after set_arm_pause: the arm is not paused");
  ASSERT_EQ(client_->request(movej({40, 0, 0, 0, 0, 0}, 50))["receive_state"], true);
  EXPECT_EQ(client_->request(plain("set_arm_pause"))["arm_pause"], true);
  EXPECT_EQ(client_->request(plain("set_delete_current_trajectory"))["delete_current_trajectory"], true);
  const auto event = client_->next_event();
  ASSERT_TRUE(event);
  EXPECT_EQ((*event)["trajectory_state"], false);
  EXPECT_EQ(client_->request(movej({0, 0, 0, 0, 0, 0}, 100))["receive_state"], true) << "free for a new motion";
}

TEST_F(RealmanSimTest, MovelKeepsTheFlangeOnAStraightLine) {
  teleport(posture_rad());
  PushReceiver push;
  push_to(push, {{"arm_current_status", true}});
  const json start = client_->request(plain("get_current_arm_state"))["arm_state"]["pose"];
  json goal = start;
  goal[1] = goal[1].get<std::int64_t>() + 50'000;  // 50 mm along y
  goal[2] = goal[2].get<std::int64_t>() + 30'000;
  ASSERT_EQ(client_->request({{"command", "movel"}, {"pose", goal}, {"v", 50}, {"r", 0}, {"trajectory_connect", 0}}),
            json({{"command", "movel"}, {"receive_state", true}}));
  double worst_off_line_um = 0;
  int moving = 0;
  const auto give_up = Clock::now() + 3s;
  while (!client_->next_event(0ms) && Clock::now() < give_up) {
    const auto datagram = push.next_json(1000ms);
    ASSERT_TRUE(datagram);
    const json& p = (*datagram)["waypoint"]["position"];
    const double t = (p[1].get<double>() - start[1].get<double>()) / 50'000;
    const double off_x = p[0].get<double>() - start[0].get<double>();
    const double off_z = p[2].get<double>() - (start[2].get<double>() + t * 30'000);
    worst_off_line_um = std::max({worst_off_line_um, std::abs(off_x), std::abs(off_z)});
    if ((*datagram)["arm_current_status"] == "move_L") ++moving;
    if (t > 1.0 + 1e-3) break;
  }
  EXPECT_LT(worst_off_line_um, 100) << "within 0.1 mm of the line";
  EXPECT_GT(moving, 50) << "about 0.8 s of move_L datagrams";
  const json end = client_->request(plain("get_current_arm_state"))["arm_state"]["pose"];
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(end[i].get<double>(), goal[i].get<double>(), 20) << "axis " << i;
}

TEST_F(RealmanSimTest, MovejPReachesThePoseInJointSpace) {
  teleport(posture_rad());
  json goal = client_->request(plain("get_current_arm_state"))["arm_state"]["pose"];
  goal[0] = goal[0].get<std::int64_t>() + 40'000;
  ASSERT_EQ(client_->request({{"command", "movej_p"}, {"pose", goal}, {"v", 80}})["receive_state"], true);
  // A joint-space move: the vendor SDK's blocking movej_p waits for "movej" and gives up on any
  // type it does not know.
  EXPECT_EQ(client_->request(plain("get_arm_current_trajectory"))["type"], "movej");
  ASSERT_TRUE(client_->next_event(2000ms));
  const json end = client_->request(plain("get_current_arm_state"))["arm_state"]["pose"];
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(end[i].get<double>(), goal[i].get<double>(), 20) << "axis " << i;
  for (std::size_t i = 3; i < 6; ++i) {
    // rx = π and rx = −π are the same turn
    EXPECT_NEAR(std::remainder(end[i].get<double>() - goal[i].get<double>(), 2000 * std::numbers::pi), 0, 2)
        << "angle " << i;
  }
  const json far = client_->request({{"command", "movej_p"}, {"pose", {2'000'000, 0, 0, 0, 0, 0}}, {"v", 80}});
  EXPECT_EQ(far["receive_state"], false);
  EXPECT_NE(far["error"].get<std::string>().find("0x1003"), std::string::npos) << far.dump();
}

TEST_F(RealmanSimTest, StepCommandsMoveFromWhereTheArmIs) {
  teleport(posture_rad());
  ASSERT_EQ(client_->request({{"command", "set_joint_step"}, {"joint_step", {6, 10000}}, {"v", 100}})["receive_state"],
            true);
  ASSERT_TRUE(client_->next_event(2000ms));
  EXPECT_NEAR(joints_deg()[5], 10, 1e-6);
  const json before = client_->request(plain("get_current_arm_state"))["arm_state"]["pose"];
  ASSERT_EQ(client_->request({{"command", "set_pos_step"}, {"step_type", "z_step"}, {"step", -20000}})
                .value("receive_state", true),
            false)
      << "v is required";
  ASSERT_EQ(client_->request(
                {{"command", "set_pos_step"}, {"step_type", "z_step"}, {"step", -20000}, {"v", 100}})["receive_state"],
            true);
  ASSERT_TRUE(client_->next_event(2000ms));
  const json after = client_->request(plain("get_current_arm_state"))["arm_state"]["pose"];
  EXPECT_NEAR(after[2].get<double>() - before[2].get<double>(), -20000, 20);
}

TEST(RealmanSimModels, CartesianMovesAreRefusedForAModelWithoutADhTable) {
  RealmanSimProcess eco({"--quiet", "--model", "ECO65-B"});
  Connection client(eco.port());
  const json reply = client.request({{"command", "movel"}, {"pose", {300000, 0, 300000, 3142, 0, 0}}, {"v", 20}});
  EXPECT_EQ(reply, json({{"command", "movel"},
                         {"receive_state", false},
                         {"error", "Cartesian planning is not emulated for ECO65-B"}}));
  EXPECT_EQ(client.request(plain("get_current_arm_state"))["arm_state"]["pose"], json({0, 0, 0, 0, 0, 0}));
}

TEST(RealmanSimModels, ASevenJointModelHasSevenJointsAndItsPose) {
  RealmanSimProcess rm75({"--quiet", "--model", "RM75-B"});
  Connection client(rm75.port());
  const json arm = client.request(plain("get_current_arm_state"))["arm_state"];
  EXPECT_EQ(arm["joint"].size(), 7U);
  EXPECT_EQ(arm["pose"][2], 850'500) << "straight up: 240.5 + 256 + 210 + 144 mm";
  EXPECT_EQ(client.request(plain("get_joint_max_pos"))["max_pos"],
            json({178000, 130000, 178000, 135000, 178000, 128000, 360000}));
  const json movel = client.request({{"command", "movel"}, {"pose", arm["pose"]}, {"v", 20}});
  EXPECT_EQ(movel["error"], "Cartesian planning is not emulated for RM75-B");
}

// --- pass-through -------------------------------------------------------------------------------

TEST_F(RealmanSimTest, PassThroughIsSilentOnGeneration3AndMovesTheJoints) {
  stream(100, 5ms, [](int k) { return std::vector<double>{0.3 * (k + 1), 0, 0, 0, 0, 0}; });
  EXPECT_FALSE(client_->next_reply(150ms)) << "gen 3 answers nothing";
  EXPECT_NEAR(joints_deg()[0], 30, 1e-6);
  const json pass = state()["pass_through"];
  EXPECT_EQ(pass["frames"], 100);
  EXPECT_EQ(pass["accepted"], 100);
  EXPECT_EQ(pass["ignored"], 0);
  EXPECT_EQ(pass["follow"], true);
  EXPECT_NEAR(pass["interval_us"]["p50"].get<double>(), 5000, 1000) << pass.dump();
  EXPECT_EQ(pass["interval_us"]["count"], 99);
}

TEST_F(RealmanSimTest, PassThroughShowsAsMoveThroughJointInThePush) {
  PushReceiver push;
  push_to(push, {{"arm_current_status", true}});
  stream(40, 5ms, [](int k) { return std::vector<double>{0.2 * (k + 1), 0, 0, 0, 0, 0}; });
  EXPECT_EQ(push.fresh_json().value_or(json())["arm_current_status"], "move_through_joint");
  std::this_thread::sleep_for(150ms);
  EXPECT_EQ(push.fresh_json().value_or(json())["arm_current_status"], "idle") << "100 ms after the last frame";
}

TEST(RealmanSimGenerations, Generation2AnswersPassThroughWithJointState) {
  RealmanSimProcess gen2({"--quiet", "--generation", "2"});
  Connection client(gen2.port());
  client.send(canfd({1, 0, 0, 0, 0, 0}));
  const auto reply = client.next_reply();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["state"], "joint_state");
  EXPECT_EQ((*reply)["arm_err"], 0);
  EXPECT_EQ((*reply)["joint"].size(), 6U);
}

TEST_F(RealmanSimTest, AFrameMoreThanTenDegreesAwayIsIgnoredAndLatches0x1007) {
  client_->send(canfd({11, 0, 0, 0, 0, 0}));
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(joints_deg()[0], 0);
  const json s = state();
  EXPECT_EQ(s["pass_through"]["ignored"], 1);
  EXPECT_EQ(s["errors"], json({0x1007}));
  EXPECT_NE(s["pass_through"]["last_rejection"].get<std::string>().find("11.000° in one frame"), std::string::npos);
  client_->send(canfd({1, 0, 0, 0, 0, 0}));
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(joints_deg()[0], 0) << "refused while the error is latched";
  EXPECT_EQ(client_->request(plain("clear_system_err"))["clear_state"], true);
  client_->send(canfd({1, 0, 0, 0, 0, 0}));
  std::this_thread::sleep_for(50ms);
  EXPECT_NEAR(joints_deg()[0], 1, 1e-6);
}

TEST_F(RealmanSimTest, AFrameFasterThan180DegreesPerSecondIsIgnored) {
  stream(60, 5ms, [](int k) { return std::vector<double>{0.1 * (k + 1), 0, 0, 0, 0, 0}; });
  std::this_thread::sleep_for(5ms);
  client_->send(canfd({6.0 + 5, 0, 0, 0, 0, 0}));  // 5° in one 5 ms frame: 1000 °/s
  std::this_thread::sleep_for(50ms);
  const json s = state();
  EXPECT_EQ(s["pass_through"]["ignored"], 1) << s["pass_through"].dump();
  EXPECT_EQ(s["errors"], json({0x1007}));
  EXPECT_NEAR(joints_deg()[0], 6, 1e-6);
}

// A client that does not set TCP_NODELAY (the vendor SDK) has its 10 ms frames coalesced by Nagle
// and delayed ACKs: several arrive in one segment, then nothing for tens of ms. The arm is
// commanded at 31 °/s all along, which is what the check judges.
TEST_F(RealmanSimTest, FramesThatArriveBatchedAreJudgedByTheirCommandedSpeed) {
  constexpr int kFrames = 100;
  constexpr int kBatch = 4;
  const auto first = Clock::now();
  for (int k = 0; k < kFrames; k += kBatch) {
    std::this_thread::sleep_until(first + k * 10ms);
    std::string batch;
    for (int i = k; i < k + kBatch; ++i) batch += frame(canfd({0.31 * (i + 1), 0, 0, 0, 0, 0}));
    client_->send_raw(batch);
  }
  std::this_thread::sleep_for(50ms);
  const json s = state();
  EXPECT_EQ(s["pass_through"]["accepted"], kFrames) << s["pass_through"].dump();
  EXPECT_EQ(s["errors"], json::array());
  EXPECT_NEAR(joints_deg()[0], 31, 1e-6);
}

TEST_F(RealmanSimTest, LowFollowLagsTheTargetBy50Ms) {
  client_->send(canfd({5, 0, 0, 0, 0, 0}, /*follow=*/false));
  std::this_thread::sleep_for(50ms);
  const double at_50ms = joints_deg()[0];
  EXPECT_NEAR(at_50ms, 5 * (1 - std::exp(-1)), 0.7) << "one time constant: 63 %";
  std::this_thread::sleep_for(400ms);
  EXPECT_NEAR(joints_deg()[0], 5, 0.01);
  EXPECT_EQ(state()["pass_through"]["follow"], false);
}

TEST_F(RealmanSimTest, APlannedMotionRefusesPassThroughFrames) {
  ASSERT_EQ(client_->request(movej({30, 0, 0, 0, 0, 0}, 50))["receive_state"], true);
  client_->send(canfd({0, 0, 0, 0, 0, 0}));
  std::this_thread::sleep_for(30ms);
  const json pass = state()["pass_through"];
  EXPECT_EQ(pass["refused"], 1);
  EXPECT_NE(pass["last_rejection"].get<std::string>().find("a trajectory is in progress"), std::string::npos);
}

// --- UDP push -----------------------------------------------------------------------------------

TEST_F(RealmanSimTest, PushArrivesEvery5MsAtTheConfiguredPort) {
  PushReceiver push;
  push_to(push);
  const int count = push.count_for(1000ms);
  EXPECT_NEAR(count, 200, 20);
  const json s = state();
  EXPECT_EQ(s["push"]["destination"], "127.0.0.1:" + std::to_string(push.port()));
}

TEST_F(RealmanSimTest, PushCycle4SendsEvery20Ms) {
  PushReceiver push;
  push_to(push, json::object(), 4);
  EXPECT_NEAR(push.count_for(1000ms), 50, 6);
}

TEST_F(RealmanSimTest, PushDatagramIsCompactJsonEndingInCrLf) {
  teleport(posture_rad());
  PushReceiver push;
  push_to(push, {{"joint_speed", true}, {"arm_current_status", true}, {"hand", true}});
  const auto datagram = push.next();
  ASSERT_TRUE(datagram);
  ASSERT_GE(datagram->size(), 2U);
  EXPECT_EQ(datagram->substr(datagram->size() - 2), "\r\n");
  EXPECT_EQ(datagram->find('\n'), datagram->size() - 1) << "one line";
  const json push_json = json::parse(*datagram);
  EXPECT_EQ(push_json["state"], "realtime_arm_joint_state");
  const json& joints = push_json["joint_status"];
  EXPECT_EQ(joints["joint_position"], json({0, 30000, 60000, 0, 60000, 0}));
  for (const char* key :
       {"joint_current", "joint_voltage", "joint_temperature", "joint_en_flag", "joint_err_code", "joint_speed"}) {
    EXPECT_EQ(joints[key].size(), 6U) << key;
  }
  EXPECT_EQ(joints["joint_en_flag"], json({1, 1, 1, 1, 1, 1}));
  const json& waypoint = push_json["waypoint"];
  EXPECT_NEAR(waypoint["position"][0].get<double>(), -410'000, 1);
  EXPECT_EQ(waypoint["quat"].size(), 4U);
  double norm = 0;
  for (const auto& q : waypoint["quat"]) norm += q.get<double>() * q.get<double>();
  EXPECT_NEAR(std::sqrt(norm), 1e6, 2);
  EXPECT_EQ(push_json["err"], json::array({0}));
  EXPECT_EQ(push_json["arm_current_status"], "idle");
  EXPECT_EQ(push_json["hand"]["hand_angle"].size(), 6U);
}

TEST_F(RealmanSimTest, JointSpeedIsPushedIn0Point01DegreesPerSecond) {
  PushReceiver push;
  push_to(push, {{"joint_speed", true}});
  ASSERT_EQ(client_->request(movej({90, 0, 0, 0, 0, 0}, 50))["receive_state"], true);
  std::this_thread::sleep_for(600ms);  // cruising at 90 °/s
  const auto datagram = push.fresh_json();
  ASSERT_TRUE(datagram);
  EXPECT_NEAR((*datagram)["joint_status"]["joint_speed"][0].get<double>(), 9000, 300);
}

TEST_F(RealmanSimTest, SetRealtimePushKeepsOmittedKeysAndRefusesBadValues) {
  ASSERT_EQ(client_->request({{"command", "set_realtime_push"}, {"cycle", 3}, {"custom", {{"hand", true}}}})["state"],
            true);
  ASSERT_EQ(client_->request({{"command", "set_realtime_push"}, {"custom", {{"joint_speed", true}}}})["state"], true);
  const json config = client_->request(plain("get_realtime_push"));
  EXPECT_EQ(config["cycle"], 3);
  EXPECT_EQ(config["port"], 8089) << "the default";
  EXPECT_EQ(config["enable"], true);
  EXPECT_EQ(config["custom"]["hand"], true);
  EXPECT_EQ(config["custom"]["joint_speed"], true);
  EXPECT_EQ(config["custom"]["arm_current_status"], false);
  const json bad_ip = client_->request({{"command", "set_realtime_push"}, {"ip", "not.an.ip"}});
  EXPECT_EQ(bad_ip["state"], false);
  EXPECT_NE(bad_ip["error"].get<std::string>().find("dotted IPv4"), std::string::npos);
  EXPECT_EQ(client_->request({{"command", "set_realtime_push"}, {"cycle", 0}})["state"], false);
  EXPECT_EQ(client_->request({{"command", "set_realtime_push"}, {"custom", {{"colour", true}}}})["error"],
            "\"custom\" has no key \"colour\"");
  EXPECT_EQ(client_->request(plain("get_realtime_push"))["cycle"], 3) << "a refused request changes nothing";
}

TEST_F(RealmanSimTest, WithoutAnIpThePushGoesToTheTcpClientsAddress) {
  PushReceiver push;
  ASSERT_EQ(client_->request({{"command", "set_realtime_push"}, {"port", push.port()}})["state"], true);
  EXPECT_TRUE(push.next());
  EXPECT_EQ(state()["push"]["ip"], "");
}

TEST_F(RealmanSimTest, PushDisabledSendsNothing) {
  PushReceiver push;
  push_to(push);
  ASSERT_EQ(client_->request({{"command", "set_realtime_push"}, {"enable", false}})["state"], true);
  EXPECT_EQ(push.count_for(100ms), 0);
}

// --- errors, enables, power ---------------------------------------------------------------------

TEST(RealmanSimErrorShapes, EachShapeWritesTheErrorsItsWay) {
  const std::vector<std::pair<const char*, json>> shapes = {
      {"list", {{"err", {0x1002, 0x5003}}}},
      {"legacy", {{"arm_err", 0x1002}, {"sys_err", 0x5003}}},
      {"scalar", {{"err", 0x1002}}},
  };
  for (const auto& [shape, expected] : shapes) {
    RealmanSimProcess sim({"--quiet", "--error-shape", shape});
    Connection client(sim.port());
    ASSERT_TRUE(sim.control({{"op", "raise_error"}, {"code", 0x1002}})["ok"].get<bool>());
    ASSERT_TRUE(sim.control({{"op", "raise_error"}, {"code", 0x5003}})["ok"].get<bool>());
    json arm_state = client.request(plain("get_current_arm_state"))["arm_state"];
    arm_state.erase("joint");
    arm_state.erase("pose");
    EXPECT_EQ(arm_state, expected) << shape;
    PushReceiver push;
    ASSERT_EQ(client.request({{"command", "set_realtime_push"}, {"port", push.port()}, {"ip", "127.0.0.1"}})["state"],
              true);
    const auto datagram = push.next_json();
    ASSERT_TRUE(datagram);
    for (const auto& [key, value] : expected.items()) EXPECT_EQ((*datagram)[key], value) << shape << " " << key;
  }
}

TEST_F(RealmanSimTest, AnErrorRefusesMotionUntilClearSystemErr) {
  control({{"op", "raise_error"}, {"code", 0x100D}});
  const json refused = client_->request(movej({10, 0, 0, 0, 0, 0}));
  EXPECT_EQ(refused["receive_state"], false);
  EXPECT_EQ(refused["error"], "the controller is in error 0x100D collision detected (clear_system_err clears it)");
  EXPECT_EQ(client_->request(plain("clear_system_err")),
            json({{"command", "clear_system_err"}, {"clear_state", true}}));
  EXPECT_EQ(client_->request(movej({10, 0, 0, 0, 0, 0}))["receive_state"], true);
}

TEST_F(RealmanSimTest, RaisingAnErrorStopsAMotionWithAFalseEvent) {
  ASSERT_EQ(client_->request(movej({60, 0, 0, 0, 0, 0}, 50))["receive_state"], true);
  std::this_thread::sleep_for(200ms);
  control({{"op", "raise_error"}, {"code", 0x1001}});
  const auto event = client_->next_event();
  ASSERT_TRUE(event);
  EXPECT_EQ((*event)["trajectory_state"], false);
}

TEST_F(RealmanSimTest, JointErrorsShowInErrFlagUntilSetJointClearErr) {
  control({{"op", "joint_error"}, {"joint", 3}, {"bits", 0x0008}});
  EXPECT_EQ(client_->request(plain("get_joint_err_flag"))["err_flag"], json({0, 0, 8, 0, 0, 0}));
  EXPECT_EQ(client_->request(plain("get_arm_all_state"))["all_state"]["err_flag"], json({0, 0, 8, 0, 0, 0}));
  EXPECT_EQ(client_->request({{"command", "set_joint_clear_err"}, {"joint_clear_err", 3}})["joint_clear_err"], true);
  EXPECT_EQ(client_->request(plain("get_joint_err_flag"))["err_flag"], json({0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(client_->request({{"command", "set_joint_clear_err"}, {"joint_clear_err", 7}})["error"],
            "\"joint_clear_err\" names joint 7; this arm has joints 1 … 6");
}

TEST_F(RealmanSimTest, ADisabledJointRefusesMotionThatMovesIt) {
  ASSERT_EQ(client_->request({{"command", "set_joint_en_state"}, {"joint_en_state", {2, 0}}})["joint_en_state"], true);
  EXPECT_EQ(client_->request(plain("get_joint_en_state"))["en_state"], json({1, 0, 1, 1, 1, 1}));
  EXPECT_EQ(client_->request(plain("get_joint_err_flag"))["brake_state"], json({0, 1, 0, 0, 0, 0}));
  const json refused = client_->request(movej({0, 10, 0, 0, 0, 0}));
  EXPECT_EQ(refused["error"], "joint 2 is disabled and would have to move");
  EXPECT_EQ(client_->request(movej({10, 0, 0, 0, 0, 0}, 100))["receive_state"], true) << "the others still move";
}

TEST_F(RealmanSimTest, PowerOffDisablesEveryJointAndRefusesMotion) {
  EXPECT_EQ(client_->request({{"command", "set_arm_power"}, {"arm_power", 0}})["arm_power"], true);
  EXPECT_EQ(client_->request(plain("get_arm_power_state"))["power_state"], 0);
  EXPECT_EQ(client_->request(plain("get_joint_en_state"))["en_state"], json({0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(client_->request(movej({10, 0, 0, 0, 0, 0}))["receive_state"], false);
  EXPECT_EQ(client_->request({{"command", "set_arm_power"}, {"arm_power", 1}})["arm_power"], true);
  EXPECT_EQ(client_->request(plain("get_joint_en_state"))["en_state"], json({1, 1, 1, 1, 1, 1}));
}

TEST_F(RealmanSimTest, EmergencyStopRefusesMotionUntilReleased) {
  EXPECT_EQ(client_->request(plain("set_arm_emergency_stop")),
            json({{"command", "set_arm_emergency_stop"}, {"arm_emergency_stop", true}}));
  EXPECT_EQ(client_->request(movej({10, 0, 0, 0, 0, 0}))["receive_state"], false);
  EXPECT_EQ(state()["status"], "stop");
  ASSERT_EQ(
      client_->request({{"command", "set_arm_emergency_stop"}, {"arm_emergency_stop", false}})["arm_emergency_stop"],
      true);
  EXPECT_EQ(client_->request(movej({10, 0, 0, 0, 0, 0}))["receive_state"], true);
}

TEST_F(RealmanSimTest, LimitsAndInitPoseAreReported) {
  EXPECT_EQ(client_->request(plain("get_joint_min_pos"))["min_pos"],
            json({-178000, -130000, -135000, -178000, -128000, -360000}));
  ASSERT_EQ(client_->request({{"command", "set_init_pose"}, {"init_pose", {0, 1000, 2000, 0, 3000, 0}}})["init_pose"],
            true);
  EXPECT_EQ(client_->request(plain("get_init_pose"))["init_pose"], json({0, 1000, 2000, 0, 3000, 0}));
  EXPECT_EQ(client_->request({{"command", "set_init_pose"}, {"init_pose", {0, 0, 200000, 0, 0, 0}}})["init_pose"],
            false);
}

TEST(RealmanSimGenerations, SoftwareInfoHasEachGenerationsShape) {
  RealmanSimProcess gen3({"--quiet"});
  Connection three(gen3.port());
  const json info3 = three.request(plain("get_arm_software_info"));
  EXPECT_EQ(info3["Product_version"], "RM65-B");
  EXPECT_FALSE(info3.contains("robot_controller_version"));
  EXPECT_TRUE(info3.contains("plan_info"));
  EXPECT_EQ(three.request(plain("get_arm_software_version"))["error"], "unknown command 'get_arm_software_version'");

  RealmanSimProcess gen4({"--quiet", "--generation", "4", "--model", "GEN72-B"});
  Connection four(gen4.port());
  const json info4 = four.request(plain("get_arm_software_info"));
  EXPECT_EQ(info4["robot_controller_version"], "4.0");
  EXPECT_EQ(info4["Product_version"], "GEN72-B");
  EXPECT_TRUE(info4["communication_info"].contains("build_time")) << "the vendor SDK refuses it without";

  RealmanSimProcess gen2({"--quiet", "--generation", "2", "--model", "RM65-B"});
  Connection two(gen2.port());
  const json version = two.request(plain("get_arm_software_version"));
  EXPECT_EQ(version["state"], "arm_software_version");
  EXPECT_EQ(version["Plan_version"], 0x6B0100);
  EXPECT_EQ(two.request(plain("get_arm_software_info"))["error"], "unknown command 'get_arm_software_info'");
  EXPECT_EQ(two.request(plain("get_realtime_push"))["error"], "unknown command 'get_realtime_push'")
      << "no UDP on gen 2";
}

// --- gripper and hand ---------------------------------------------------------------------------

TEST_F(RealmanSimTest, AGripperPickAtFullSpeedTakesHalfASecondAndEndsWithABlockEvent) {
  const auto start = Clock::now();
  EXPECT_EQ(client_->request({{"command", "set_gripper_pick"}, {"speed", 1000}, {"force", 200}, {"block", true}}),
            json({{"command", "set_gripper"}, {"state", true}}));
  EXPECT_EQ(client_->request(plain("get_gripper_state"))["mode"], 4) << "closing";
  const auto event = client_->next_event();
  ASSERT_TRUE(event);
  EXPECT_EQ(*event, json({{"state", "current_trajectory_state"},
                          {"trajectory_state", true},
                          {"device", 1},
                          {"trajectory_connect", 0}}))
      << "the vendor SDK refuses a completion without trajectory_connect";
  EXPECT_NEAR(std::chrono::duration<double>(Clock::now() - start).count(), 0.5, 0.06);
  const json gripper = client_->request(plain("get_gripper_state"));
  EXPECT_EQ(gripper, json({{"command", "get_gripper_state"},
                           {"enable", 1},
                           {"status", 1},
                           {"error", 0},
                           {"mode", 2},
                           {"current_force", 0},
                           {"temperature", 40},
                           {"actpos", 0}}));
}

TEST_F(RealmanSimTest, APickStopsOnAPlacedObjectWithMode6) {
  control({{"op", "place_object"}, {"opening", 400}});
  ASSERT_EQ(
      client_->request({{"command", "set_gripper_pick"}, {"speed", 1000}, {"force", 300}, {"block", true}})["state"],
      true);
  ASSERT_TRUE(client_->next_event());
  const json gripper = client_->request(plain("get_gripper_state"));
  EXPECT_EQ(gripper["mode"], 6);
  EXPECT_EQ(gripper["actpos"], 400);
  EXPECT_EQ(gripper["current_force"], 300);
  control({{"op", "remove_object"}});
  EXPECT_EQ(client_->request(plain("get_gripper_state"))["mode"], 3) << "a pick does not close again";
}

TEST_F(RealmanSimTest, PickOnClosesAgainWhenTheObjectGoes) {
  control({{"op", "place_object"}, {"opening", 600}});
  ASSERT_EQ(
      client_->request({{"command", "set_gripper_pick_on"}, {"speed", 1000}, {"force", 100}, {"block", true}})["state"],
      true);
  ASSERT_TRUE(client_->next_event());
  control({{"op", "remove_object"}});
  EXPECT_EQ(client_->request(plain("get_gripper_state"))["mode"], 4);
  std::this_thread::sleep_for(400ms);
  EXPECT_EQ(client_->request(plain("get_gripper_state"))["actpos"], 0);
}

TEST_F(RealmanSimTest, TheGripperRouteBoundsItsStroke) {
  ASSERT_EQ(client_->request({{"command", "set_gripper_route"}, {"min", 70}, {"max", 500}})["state"], true);
  ASSERT_EQ(client_->request({{"command", "set_gripper_position"}, {"position", 900}, {"block", true}})["state"], true);
  ASSERT_TRUE(client_->next_event());
  EXPECT_EQ(client_->request(plain("get_gripper_state"))["actpos"], 500);
  EXPECT_EQ(client_->request(plain("get_gripper_state"))["mode"], 1) << "open: at the route's max";
  const json reversed = client_->request({{"command", "set_gripper_route"}, {"min", 600}, {"max", 500}});
  EXPECT_EQ(reversed,
            json({{"command", "set_gripper_route"}, {"state", false}, {"error", "\"min\" 600 is above \"max\" 500"}}));
  EXPECT_EQ(client_->request({{"command", "set_gripper_position"}, {"position", 0}})["state"], false);
}

TEST_F(RealmanSimTest, HandAngleMinusOneKeepsThatDegreeOfFreedom) {
  ASSERT_EQ(client_->request(
                {{"command", "set_hand_angle"}, {"hand_angle", {100, 200, 300, 400, 500, 600}}, {"block", true}}),
            json({{"command", "set_hand_angle"}, {"set_state", true}}));
  const auto event = client_->next_event(2000ms);
  ASSERT_TRUE(event);
  EXPECT_EQ(*event, json({{"state", "current_trajectory_state"},
                          {"trajectory_state", true},
                          {"device", 2},
                          {"trajectory_connect", 0}}));
  ASSERT_EQ(
      client_->request(
          {{"command", "set_hand_angle"}, {"hand_angle", {-1, -1, 0, -1, -1, 999}}, {"block", true}})["set_state"],
      true);
  ASSERT_TRUE(client_->next_event(2000ms));
  EXPECT_EQ(state()["hand"]["angles"], json({100, 200, 0, 400, 500, 999}));
  EXPECT_EQ(client_->request({{"command", "set_hand_angle"}, {"hand_angle", {-2, 0, 0, 0, 0, 0}}})["set_state"], false);
}

TEST_F(RealmanSimTest, HandPosturesAndSequencesAreTheDocumentedTables) {
  ASSERT_EQ(client_->request({{"command", "set_hand_posture"}, {"posture_num", 40}, {"block", true}})["set_state"],
            true);
  EXPECT_EQ(client_->next_event(3000ms).value_or(json()), json({{"state", "current_trajectory_state"},
                                                                {"trajectory_state", true},
                                                                {"device", 2},
                                                                {"trajectory_connect", 0}}));
  EXPECT_EQ(state()["hand"]["angles"], json({0, 0, 0, 0, 0, 0}));
  ASSERT_EQ(client_->request({{"command", "set_hand_seq"}, {"seq_num", 20}, {"block", true}})["set_state"], true);
  ASSERT_TRUE(client_->next_event(5000ms));
  EXPECT_EQ(state()["hand"]["angles"], json({1000, 1000, 1000, 1000, 1000, 1000})) << "a sequence ends open";
  EXPECT_EQ(client_->request({{"command", "set_hand_posture"}, {"posture_num", 41}})["set_state"], false);
}

TEST_F(RealmanSimTest, AMoveThatReplacesAnAwaitedOneEndsItWithFalse) {
  ASSERT_EQ(
      client_->request({{"command", "set_gripper_pick"}, {"speed", 100}, {"force", 200}, {"block", true}})["state"],
      true);
  ASSERT_EQ(client_->request({{"command", "set_gripper_release"}, {"speed", 1000}, {"block", true}})["state"], true);
  EXPECT_EQ(client_->next_event().value_or(json())["trajectory_state"], false);
  EXPECT_EQ(client_->next_event().value_or(json())["trajectory_state"], true);
}

// --- control channel ----------------------------------------------------------------------------

TEST_F(RealmanSimTest, GarbageReachesTheClientAndThePushWithoutBreakingEither) {
  PushReceiver push;
  push_to(push);
  const json reply = control({{"op", "garbage"}});
  EXPECT_EQ(reply["lines"], 1);
  EXPECT_EQ(reply["datagram"], true);
  EXPECT_EQ(client_->request(plain("get_joint_degree"))["state"], "joint_degree");
  EXPECT_EQ(client_->unreadable().size(), 1U);
  bool garbage_datagram = false;
  for (int i = 0; i < 50 && !garbage_datagram; ++i) {
    const auto datagram = push.next();
    ASSERT_TRUE(datagram);
    garbage_datagram = json::parse(*datagram, nullptr, false).is_discarded();
  }
  EXPECT_TRUE(garbage_datagram);
  EXPECT_TRUE(push.next_json().value_or(json()).contains("joint_status")) << "pushing on";
}

TEST_F(RealmanSimTest, DisconnectClosesTheClientsAndKeepsListening) {
  Connection other(sim_->port());
  ASSERT_EQ(other.request(plain("get_joint_degree"))["state"], "joint_degree");
  EXPECT_EQ(control({{"op", "disconnect"}})["closed"], 2);
  EXPECT_TRUE(client_->closed_within(500ms));
  EXPECT_TRUE(other.closed_within(500ms));
  Connection again(sim_->port());
  EXPECT_EQ(again.request(plain("get_joint_degree"))["state"], "joint_degree");
}

TEST_F(RealmanSimTest, DropRepliesSwallowsTheNextN) {
  control({{"op", "drop_replies"}, {"count", 2}});
  client_->send(plain("get_joint_degree"));
  client_->send(plain("get_arm_power_state"));
  EXPECT_FALSE(client_->next_reply(150ms));
  EXPECT_EQ(client_->request(plain("get_joint_en_state"))["state"], "joint_en_state");
  const json s = state();
  EXPECT_EQ(s["replies_dropped"], 2);
  EXPECT_EQ(s["commands"]["get_joint_degree"], 1) << "they were carried out";
}

TEST_F(RealmanSimTest, SilenceStopsThePushButNotTheCommandChannel) {
  PushReceiver push;
  push_to(push);
  control({{"op", "silence"}, {"on", true}});
  EXPECT_EQ(push.count_for(200ms), 0);
  EXPECT_EQ(client_->request(plain("get_joint_degree"))["state"], "joint_degree");
  control({{"op", "silence"}, {"on", false}});
  EXPECT_GT(push.count_for(200ms), 30);
}

TEST_F(RealmanSimTest, ARaisedErrorShowsInThePush) {
  PushReceiver push;
  push_to(push);
  control({{"op", "raise_error"}, {"code", 0x1007}});
  EXPECT_EQ(push.fresh_json().value_or(json())["err"], json({0x1007}));
  control({{"op", "clear"}});
  EXPECT_EQ(push.fresh_json().value_or(json())["err"], json::array({0}));
}

TEST_F(RealmanSimTest, SetJointsTeleportsTheArm) {
  control({{"op", "set_joints"}, {"joints_rad", {0.5, 0, 0, 0, 0, 0}}});
  EXPECT_EQ(client_->request(plain("get_joint_degree"))["joint"][0], std::llround(0.5 / kDeg * 1000));
}

TEST_F(RealmanSimTest, ControlRefusesBadRequestsWithReasons) {
  const auto expect_error = [this](const json& request, const std::string& part) {
    const json reply = sim_->control(request);
    EXPECT_FALSE(reply.value("ok", true)) << request.dump();
    EXPECT_NE(reply.value("error", "").find(part), std::string::npos) << request.dump() << " -> " << reply.dump();
  };
  expect_error({{"op", "fly"}}, "unknown op \"fly\"");
  expect_error({{"op", "raise_error"}}, "\"code\"");
  expect_error({{"op", "joint_error"}, {"joint", 7}, {"bits", 1}}, "\"joint\"");
  expect_error({{"op", "silence"}, {"on", 1}}, "true or false");
  expect_error({{"op", "place_object"}, {"opening", 1001}}, "\"opening\"");
  expect_error({{"op", "set_joints"}, {"joints_rad", {0, 0}}}, "6 numbers (rad)");
  expect_error({{"op", "set_joints"}, {"joints_rad", {0, 0, 3, 0, 0, 0}}}, "joint 3 target");
  expect_error({{"op", "state"}, {"verbose", true}}, "does not take \"verbose\"");
  EXPECT_TRUE(state()["ok"].get<bool>()) << "still serving";
}

// --- the process --------------------------------------------------------------------------------

TEST_F(RealmanSimTest, RestartedItListensOnTheSamePort) {
  const std::uint16_t port = sim_->port();
  sim_->kill_hard();
  EXPECT_TRUE(client_->closed_within(500ms));
  sim_->restart();
  EXPECT_EQ(sim_->port(), port);
  Connection again(port);
  EXPECT_EQ(again.request(plain("get_joint_degree"))["state"], "joint_degree");
}

TEST_F(RealmanSimTest, SigtermEndsItCleanly) { EXPECT_EQ(sim_->terminate(), 0); }

TEST(RealmanSimCommandLine, BadOptionsExitWith2) {
  const std::string port = std::to_string(RealmanSimProcess::free_port());
  EXPECT_EQ(run_to_exit({}), 2) << "no --port";
  EXPECT_EQ(run_to_exit({"--port", "70000"}), 2);
  EXPECT_EQ(run_to_exit({"--port", port, "--model", "RM99-B"}), 2);
  EXPECT_EQ(run_to_exit({"--port", port, "--generation", "5"}), 2);
  EXPECT_EQ(run_to_exit({"--port", port, "--error-shape", "tuple"}), 2);
  EXPECT_EQ(run_to_exit({"--port", port, "--bogus"}), 2);
}

TEST(RealmanSimCommandLine, APortInUseExitsWith2) {
  const RealmanSimProcess first({"--quiet"});
  EXPECT_EQ(run_to_exit({"--port", std::to_string(first.port()), "--quiet"}), 2);
  EXPECT_TRUE(first.control({{"op", "state"}})["ok"].get<bool>()) << "the first one is unharmed";
}

}  // namespace
}  // namespace robotd::realman
