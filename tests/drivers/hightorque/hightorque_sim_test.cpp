// robotd-hightorque-sim as a driver sees it: a real process with CAN-FD stand-in buses (joined
// with transport::make_can_transport) and USB-CDC board ports (ptys opened with
// transport::SerialPort), spoken to with the codec and steered through its control channel.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "codec/hightorque_codec.hpp"
#include "hightorque_sim_process.hpp"
#include "robotd/transport/can_transport.hpp"
#include "robotd/transport/serial_port.hpp"

namespace robotd::hightorque {
namespace {

using namespace std::chrono_literals;
using testing::HighTorqueSimProcess;
using transport::CanIo;
using transport::CanMessage;
using Clock = std::chrono::steady_clock;

constexpr int kMaxMotor = 126;
constexpr double kBoardTorqueUnit = 0.004938;  // the 5047_36, the simulator's default model
constexpr std::uint8_t kTimeoutFault = 0x15;
const MotorScaling kScaling{};
const std::array<MotorScaling, kMaxMotorId + 1> kScalingById{};  // encode_block's, by motor id

MotorCommand mit(double position, double kp, double kd, double velocity = 0, double torque = 0) {
  MotorCommand command;
  command.mode = Mode::kMit;
  command.position_rad = position;
  command.velocity_rad_s = velocity;
  command.torque_nm = torque;
  command.kp = kp;
  command.kd = kd;
  return command;
}

MotorCommand mode_only(Mode mode) {
  MotorCommand command;
  command.mode = mode;
  return command;
}

/// Drains `receive` until `done()` holds or `timeout` passes.
bool wait_until(const std::function<void()>& receive, const std::function<bool()>& done,
                std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (Clock::now() < deadline) {
    receive();
    if (done()) return true;
    std::this_thread::sleep_for(1ms);
  }
  return false;
}

class HighTorqueSimTest : public ::testing::Test {
 protected:
  void start(const std::vector<HighTorqueSimProcess::Link>& links, std::vector<std::string> extra = {}) {
    link_.reset();
    extra.emplace_back("--quiet");
    sim_ = std::make_unique<HighTorqueSimProcess>(links, std::move(extra));
  }
  void start_bus(const std::string& ids = "1-6", std::vector<std::string> extra = {}) {
    start({HighTorqueSimProcess::standin(ids)}, std::move(extra));
    connect();
  }

  void connect(std::size_t bus = 0) {
    transport::CanLinkConfig config;
    config.kind = transport::CanLinkConfig::Kind::kStandIn;
    config.path = sim_->bus_path(bus);
    link_ = transport::make_can_transport(config);
    auto opened = link_->open();
    ASSERT_TRUE(opened) << opened.error().message;
    replies_.clear();
  }

  void send(const CanMessage& message) { ASSERT_EQ(link_->send(message), CanIo::kDone); }
  void command(int motor, const MotorCommand& command, Query query = Query::kState, Width width = Width::kInt16) {
    send(encode_command(motor, command, width, query, kScaling));
  }

  /// Takes every waiting frame into replies_ (undecodable ones count in undecodable_).
  CanIo drain() {
    CanMessage message;
    while (true) {
      const CanIo result = link_->receive(message);
      if (result == CanIo::kNone || result == CanIo::kClosed) return result;
      if (result != CanIo::kDone) continue;
      if (auto reply = decode_reply(message, kMaxMotor, kScaling)) {
        replies_.push_back(*reply);
      } else {
        ++undecodable_;
      }
    }
  }
  /// Waits until `count` replies are in (or `timeout`); takes them all.
  std::vector<Reply> replies(std::size_t count, std::chrono::milliseconds timeout = 500ms) {
    wait_until([this] { drain(); }, [&] { return replies_.size() >= count; }, timeout);
    std::vector<Reply> out;
    out.swap(replies_);
    return out;
  }
  std::vector<Reply> replies_for(std::chrono::milliseconds window) {
    return replies(std::numeric_limits<std::size_t>::max(), window);
  }
  /// One state reply of `motor` to a plain query.
  std::optional<MotorState> query(int motor, Query query_code = Query::kState) {
    replies_.clear();
    send(encode_query(motor, query_code, Width::kInt16));
    for (const Reply& reply : replies(1)) {
      if (reply.kind == Reply::Kind::kState && reply.state.motor == motor) return reply.state;
    }
    return std::nullopt;
  }
  /// Sends `request` and waits for a 0x03 result reply (other replies, e.g. pushed ones, are dropped).
  std::optional<CommandResult> result_of(const CanMessage& request) {
    replies_.clear();
    send(request);
    std::optional<CommandResult> result;
    wait_until(
        [this, &result] {
          drain();
          for (const Reply& reply : replies_) {
            if (reply.kind == Reply::Kind::kResult) result = reply.result;
          }
          replies_.clear();
        },
        [&result] { return result.has_value(); }, 500ms);
    return result;
  }

  nlohmann::json control(const nlohmann::json& request) {
    nlohmann::json reply = sim_->control(request);
    EXPECT_TRUE(reply.value("ok", false)) << request.dump() << " -> " << reply.dump();
    return reply;
  }
  nlohmann::json motor(int id, std::size_t bus = 0) { return sim_->motor_state(bus, id); }

  std::unique_ptr<HighTorqueSimProcess> sim_;
  std::unique_ptr<transport::CanTransport> link_;
  std::vector<Reply> replies_;
  int undecodable_ = 0;
};

TEST_F(HighTorqueSimTest, MitFrameMovesTheMotorTowardTheTargetAndReplies) {
  start_bus("1-6");
  command(1, mit(1.0, 20, 1), Query::kState, Width::kInt32);
  const auto first = replies(1);
  ASSERT_EQ(first.size(), 1U);
  EXPECT_EQ(first[0].kind, Reply::Kind::kState);
  EXPECT_EQ(first[0].state.motor, 1);
  EXPECT_EQ(first[0].state.query, Query::kState);
  EXPECT_EQ(first[0].state.mode, static_cast<std::uint8_t>(Mode::kMit));
  EXPECT_EQ(first[0].state.fault, 0);

  std::optional<MotorState> state;
  ASSERT_TRUE(
      wait_until([&] { state = query(1); }, [&] { return state && std::abs(state->position_rad - 1.0) < 0.01; }, 3s))
      << "motor 1 never reached 1 rad";
  const nlohmann::json entry = motor(1);
  EXPECT_EQ(entry["mode"], "mit");
  EXPECT_EQ(entry["mode_code"], 0x21);
  EXPECT_NEAR(entry["kp"].get<double>(), 20, 0.02);  // one wire LSB of an int16 gain: 0.1 / 2π
  EXPECT_NEAR(entry["kd"].get<double>(), 1, 0.02);
  EXPECT_NEAR(motor(2)["position_rad"].get<double>(), 0, 1e-9) << "only motor 1 was commanded";
}

TEST_F(HighTorqueSimTest, StiffGainsStayStableAndTorqueSaturates) {
  start_bus("1", {"--torque-max", "10"});
  command(1, mit(0.5, 500, 50));
  ASSERT_TRUE(wait_until([] {}, [&] { return std::abs(motor(1)["position_rad"].get<double>() - 0.5) < 1e-3; }, 3s));
  // Settled, not oscillating.
  EXPECT_LT(std::abs(motor(1)["velocity_rad_s"].get<double>()), 1e-2);
  command(1, mit(5.0, 500, 5));
  std::this_thread::sleep_for(20ms);
  EXPECT_NEAR(motor(1)["torque_nm"].get<double>(), 10, 1e-6) << "saturates at --torque-max";
}

TEST_F(HighTorqueSimTest, BlockFrameForSixMotorsGetsSixReplies) {
  start_bus("1-6");
  std::vector<BlockSlot> slots;
  for (int id = 1; id <= 6; ++id) slots.push_back(BlockSlot{.motor = id, .command = mit(0.1 * id, 10, 1)});
  std::array<CanMessage, 5> frames{};
  const std::size_t count = encode_block(slots, Query::kState, kScalingById, 6, frames);
  ASSERT_EQ(count, 1U);
  send(frames[0]);
  auto got = replies(6);
  ASSERT_EQ(got.size(), 6U);
  std::vector<int> ids;
  for (const Reply& reply : got) {
    EXPECT_EQ(reply.kind, Reply::Kind::kState);
    EXPECT_EQ(reply.state.mode, static_cast<std::uint8_t>(Mode::kMit));
    ids.push_back(reply.state.motor);
  }
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(ids, (std::vector<int>{1, 2, 3, 4, 5, 6}));
  EXPECT_TRUE(replies_for(50ms).empty()) << "exactly one reply per slot";
  for (int id = 1; id <= 6; ++id) EXPECT_NEAR(motor(id)["target_position_rad"].get<double>(), 0.1 * id, 1e-3);
}

TEST_F(HighTorqueSimTest, UnsetBlockSlotsKeepTheirPreviousValues) {
  start_bus("1-6");
  command(2, mit(0.5, 10, 1, 0, 0.2));
  ASSERT_EQ(replies(1).size(), 1U);
  MotorCommand partial = mit(std::numeric_limits<double>::quiet_NaN(), 30, std::numeric_limits<double>::quiet_NaN());
  partial.torque_nm = std::numeric_limits<double>::quiet_NaN();
  const std::array<BlockSlot, 1> slots{BlockSlot{.motor = 2, .command = partial}};
  std::array<CanMessage, 5> frames{};
  ASSERT_EQ(encode_block(slots, Query::kState, kScalingById, 6, frames), 1U);
  send(frames[0]);
  ASSERT_EQ(replies(1).size(), 1U);
  const nlohmann::json entry = motor(2);
  EXPECT_NEAR(entry["target_position_rad"].get<double>(), 0.5, 1e-3);
  EXPECT_NEAR(entry["kp"].get<double>(), 30, 0.02);  // one wire LSB: 0.1 / 2π
  EXPECT_NEAR(entry["kd"].get<double>(), 1, 0.02);
  EXPECT_NEAR(entry["target_torque_nm"].get<double>(), 0.2, 0.01);
}

TEST_F(HighTorqueSimTest, CommandTimeoutBrakesWithFault0x15UntilTheNextCommand) {
  start_bus("1-2");
  const auto armed = result_of(encode_command_timeout(1, 100));
  ASSERT_TRUE(armed);
  EXPECT_TRUE(armed->success);
  command(1, mit(0, 0, 0.5));
  ASSERT_EQ(replies(1).size(), 1U);
  EXPECT_EQ(motor(1)["timeout_ms"], 100);
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(motor(1)["fault"], 0) << "not yet";
  ASSERT_TRUE(wait_until([] {}, [&] { return motor(1)["fault"] == kTimeoutFault; }, 1s)) << "the watchdog never fired";
  EXPECT_EQ(motor(1)["mode"], "brake");
  EXPECT_EQ(motor(2)["fault"], 0) << "motor 2's watchdog was never armed";
  const auto reported = query(1);
  ASSERT_TRUE(reported);
  EXPECT_EQ(reported->fault, kTimeoutFault);
  EXPECT_EQ(reported->mode, static_cast<std::uint8_t>(Mode::kBrake));
  EXPECT_EQ(motor(1)["fault"], kTimeoutFault) << "a query does not clear it";

  command(1, mit(0, 0, 0.5));
  const auto cleared = replies(1);
  ASSERT_EQ(cleared.size(), 1U);
  EXPECT_EQ(cleared[0].state.fault, 0);
  EXPECT_EQ(cleared[0].state.mode, static_cast<std::uint8_t>(Mode::kMit));
}

TEST_F(HighTorqueSimTest, BrakeDampsAnExternalTorqueAndStopFreeWheels) {
  start_bus("1-2");
  control({{"op", "push_external_torque"}, {"bus", 0}, {"motor", 1}, {"torque_nm", 1.0}});
  control({{"op", "push_external_torque"}, {"bus", 0}, {"motor", 2}, {"torque_nm", 1.0}});
  command(1, mode_only(Mode::kBrake), Query::kNone);
  command(2, mode_only(Mode::kStop), Query::kNone);
  std::this_thread::sleep_for(500ms);
  // BRAKE: 1 N·m against 2 + 0.05 N·m·s/rad; STOP: only friction, J/b = 0.4 s to 20 rad/s.
  EXPECT_NEAR(motor(1)["velocity_rad_s"].get<double>(), 1.0 / 2.05, 0.02);
  EXPECT_GT(motor(2)["velocity_rad_s"].get<double>(), 5.0);
  EXPECT_EQ(motor(1)["mode"], "brake");
}

TEST_F(HighTorqueSimTest, SetZeroMakesTheCurrentPositionZero) {
  start_bus("1");
  control({{"op", "set_position"}, {"bus", 0}, {"motor", 1}, {"position_rad", 1.25}});
  const auto before = query(1);
  ASSERT_TRUE(before);
  EXPECT_NEAR(before->position_rad, 1.25, 1e-3);
  const auto zeroed = result_of(encode_set_zero(1));
  ASSERT_TRUE(zeroed);
  EXPECT_TRUE(zeroed->success);
  EXPECT_EQ(zeroed->code, 0);
  const auto after = query(1);
  ASSERT_TRUE(after);
  EXPECT_NEAR(after->position_rad, 0, 1e-3);
  EXPECT_NEAR(motor(1)["zero_offset_rad"].get<double>(), 1.25, 1e-6);
  const auto rebooted = result_of(encode_soft_reboot(1));
  ASSERT_TRUE(rebooted);
  EXPECT_TRUE(rebooted->success);
  EXPECT_NEAR(motor(1)["zero_offset_rad"].get<double>(), 1.25, 1e-6) << "a reboot keeps the zero";
  EXPECT_EQ(motor(1)["mode"], "stop");
}

TEST_F(HighTorqueSimTest, InfoRequestsAnswerVersionsAndModel) {
  start_bus("3", {"--model", "6056_36", "--firmware", "1.2.3"});
  send(encode_info_request(3, InfoKind::kFirmwareVersion));
  send(encode_info_request(3, InfoKind::kHardwareVersion));
  send(encode_info_request(3, InfoKind::kModel));
  const auto got = replies(3);
  ASSERT_EQ(got.size(), 3U);
  EXPECT_EQ(got[0].kind, Reply::Kind::kFirmwareVersion);
  EXPECT_EQ(got[0].version.motor, 3);
  EXPECT_EQ(got[0].version.major, 1);
  EXPECT_EQ(got[0].version.minor, 2);
  EXPECT_EQ(got[0].version.patch, 3);
  EXPECT_EQ(got[1].kind, Reply::Kind::kHardwareVersion);
  EXPECT_EQ(got[1].version.major, 1);
  EXPECT_EQ(got[2].kind, Reply::Kind::kModel);
  EXPECT_STREQ(got[2].model.text.data(), "6056_36");
}

TEST_F(HighTorqueSimTest, StatusPushSendsRepliesByItself) {
  start_bus("1");
  const auto refused = result_of(encode_status_push(1, Query::kState, 50));
  ASSERT_TRUE(refused);
  EXPECT_FALSE(refused->success) << "under 100 µs is refused";
  const auto accepted = result_of(encode_status_push(1, Query::kStateTemperature, 10'000));
  ASSERT_TRUE(accepted);
  EXPECT_TRUE(accepted->success);
  const auto pushed = replies_for(300ms);
  EXPECT_GE(pushed.size(), 20U);
  EXPECT_LE(pushed.size(), 32U);
  for (const Reply& reply : pushed) {
    ASSERT_EQ(reply.kind, Reply::Kind::kState);
    EXPECT_EQ(reply.state.query, Query::kStateTemperature);
    ASSERT_TRUE(reply.state.temperature_c);
    EXPECT_NEAR(*reply.state.temperature_c, 30, 1);
  }
  ASSERT_TRUE(result_of(encode_status_push(1, Query::kState, 0)));
  replies_for(30ms);
  EXPECT_TRUE(replies_for(100ms).empty()) << "period 0 stops it";
}

TEST_F(HighTorqueSimTest, ChangeIdAnswersOnTheNewId) {
  start_bus("1-3");
  const auto changed = result_of(encode_change_id(3, 9).value());
  ASSERT_TRUE(changed);
  EXPECT_TRUE(changed->success);
  EXPECT_EQ(changed->motor, 3);
  EXPECT_TRUE(query(9));
  EXPECT_FALSE(query(3));
  const auto taken = result_of(encode_change_id(9, 1).value());
  ASSERT_TRUE(taken);
  EXPECT_FALSE(taken->success) << "motor 1 is on the bus already";
}

TEST_F(HighTorqueSimTest, InjectedFaultFreeWheelsUntilCleared) {
  start_bus("1-2");
  command(1, mit(0.5, 20, 1));
  ASSERT_EQ(replies(1).size(), 1U);
  control({{"op", "set_fault"}, {"bus", 0}, {"motor", 1}, {"code", 0x0D}});
  command(1, mit(0.5, 20, 1));
  auto faulted = replies(1);
  ASSERT_EQ(faulted.size(), 1U);
  EXPECT_EQ(faulted[0].state.fault, 0x0D);
  EXPECT_EQ(faulted[0].state.mode, static_cast<std::uint8_t>(Mode::kStop)) << "not obeyed while faulted";
  EXPECT_EQ(motor(1)["mode"], "stop");
  EXPECT_EQ(motor(2)["fault"], 0);
  control({{"op", "clear_fault"}, {"bus", 0}, {"motor", 1}});
  command(1, mit(0.5, 20, 1));
  auto cleared = replies(1);
  ASSERT_EQ(cleared.size(), 1U);
  EXPECT_EQ(cleared[0].state.fault, 0);
  EXPECT_EQ(cleared[0].state.mode, static_cast<std::uint8_t>(Mode::kMit));
}

TEST_F(HighTorqueSimTest, OverTemperatureRaisesFault0x14) {
  start_bus("1");
  control({{"op", "set_temperature"}, {"bus", 0}, {"motor", 1}, {"celsius", 95}});
  ASSERT_TRUE(wait_until([] {}, [&] { return motor(1)["fault"] == 0x14; }, 1s));
  const auto state = query(1, Query::kStateTemperature);
  ASSERT_TRUE(state);
  EXPECT_EQ(state->fault, 0x14);
  ASSERT_TRUE(state->temperature_c);
  EXPECT_NEAR(*state->temperature_c, 95, 1.01);
}

TEST_F(HighTorqueSimTest, MutedMotorNeitherObeysNorReplies) {
  start_bus("1-2");
  control({{"op", "mute"}, {"bus", 0}, {"motor", 2}, {"on", true}});
  command(2, mit(1, 20, 1));
  command(1, mit(0, 0, 1));
  const auto got = replies_for(100ms);
  ASSERT_EQ(got.size(), 1U);
  EXPECT_EQ(got[0].state.motor, 1);
  EXPECT_EQ(motor(2)["mode"], "stop");
  EXPECT_EQ(motor(2)["commands"], 0);
  control({{"op", "mute"}, {"bus", 0}, {"motor", 2}, {"on", false}});
  EXPECT_TRUE(query(2));
}

TEST_F(HighTorqueSimTest, DropRepliesLosesExactlyThatMany) {
  start_bus("1");
  control({{"op", "drop_replies"}, {"bus", 0}, {"count", 3}});
  for (int i = 0; i < 5; ++i) send(encode_query(1, Query::kState, Width::kInt16));
  EXPECT_EQ(replies_for(150ms).size(), 2U);
  EXPECT_EQ(motor(1)["commands"], 5) << "the motor heard them all";
  const auto bus = sim_->state()["buses"][0];
  EXPECT_EQ(bus["replies_dropped"], 3);
  EXPECT_EQ(bus["frames_received"], 5);
  EXPECT_EQ(bus["frames_sent"], 2);
  control({{"op", "reset_counters"}});
  EXPECT_EQ(sim_->state()["buses"][0]["frames_received"], 0);
}

TEST_F(HighTorqueSimTest, SilenceLosesEveryReplyForAWhileAndTheLinkStaysUp) {
  start_bus("1-2");
  control({{"op", "silence"}, {"bus", 0}, {"for_ms", 200}});
  send(encode_query(1, Query::kState, Width::kInt16));
  send(encode_query(2, Query::kState, Width::kInt16));
  EXPECT_TRUE(replies_for(100ms).empty());
  EXPECT_EQ(motor(2)["commands"], 1) << "the motors heard";
  std::this_thread::sleep_for(150ms);
  send(encode_query(1, Query::kState, Width::kInt16));
  EXPECT_EQ(replies_for(100ms).size(), 1U) << "answering again once the silence is over";
}

TEST_F(HighTorqueSimTest, GarbageNeverDecodes) {
  start_bus("1-6");
  control({{"op", "garbage"}, {"bus", 0}, {"count", 200}});
  EXPECT_TRUE(replies_for(200ms).empty());
  EXPECT_EQ(undecodable_, 200);
}

TEST_F(HighTorqueSimTest, UnknownFramesCountAsBad) {
  start_bus("1");
  CanMessage reply_shaped = encode_query(1, Query::kState, Width::kInt16);
  reply_shaped.id = reply_id(Width::kInt16, 1);  // bit 15 clear: not a command
  send(reply_shaped);
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(sim_->state()["buses"][0]["bad_frames"], 1);
}

TEST_F(HighTorqueSimTest, DisconnectClosesTheBusAndItComesBack) {
  start_bus("1");
  control({{"op", "disconnect"}, {"bus", 0}, {"for_ms", 300}});
  ASSERT_TRUE(wait_until([] {}, [&] { return drain() == CanIo::kClosed; }, 500ms)) << "the link never closed";
  ASSERT_TRUE(wait_until([] {}, [&] { return sim_->state()["buses"][0]["open"] == true; }, 2s));
  connect();
  EXPECT_TRUE(query(1));
}

TEST_F(HighTorqueSimTest, TwoBusesAreIndependent) {
  start({HighTorqueSimProcess::standin("1-2"), HighTorqueSimProcess::standin("1-2")});
  connect(1);
  command(1, mit(0.3, 10, 1));
  ASSERT_EQ(replies(1).size(), 1U);
  EXPECT_EQ(motor(1, 1)["mode"], "mit");
  EXPECT_EQ(motor(1, 0)["mode"], "stop");
  EXPECT_EQ(sim_->state()["buses"][1]["kind"], "standin");
}

// ---- The USB-CDC board on a pty ------------------------------------------------------------

/// The host end of a board port: a SerialPort and the packet splitter.
class BoardHost {
 public:
  explicit BoardHost(const std::string& device) : port_(transport::SerialConfig{.device = device, .baud = 3'000'000}) {
    scaling_.fill(MotorScaling{.torque_per_unit = kBoardTorqueUnit, .torque_offset_nm = 0, .gain_factor = 1});
  }
  Result<void> open() { return port_.open(); }
  void send_bytes(std::span<const std::uint8_t> bytes) {
    std::size_t written = 0;
    ASSERT_EQ(port_.write(bytes, written), transport::SerialIo::kDone);
    ASSERT_EQ(written, bytes.size());
  }
  void send(BoardCommand command, std::span<const std::uint8_t> payload) {
    std::vector<std::uint8_t> packet(kBoardHeaderSize + kMaxBoardPayload);
    const std::size_t size = encode_board_frame(command, payload, packet);
    ASSERT_GT(size, 0U);
    packet.resize(size);
    send_bytes(packet);
  }
  /// One packet of a port whose highest motor is the highest of `slots`.
  void send_slots(BoardCommand command, std::span<const BlockSlot> slots) {
    int highest = 0;
    for (const BlockSlot& slot : slots) highest = std::max(highest, slot.motor);
    BoardSlotBuffer buffer(highest);
    const std::span<const std::uint8_t> payload = buffer.update(command, slots, scaling_);
    ASSERT_FALSE(payload.empty());
    send(command, payload);
  }
  /// Packets read until `count` arrived or `timeout` passed.
  std::vector<BoardFrame> receive(std::size_t count, std::chrono::milliseconds timeout = 500ms) {
    std::vector<BoardFrame> frames;
    wait_until(
        [&] {
          std::array<std::uint8_t, 2048> chunk{};
          std::size_t n = 0;
          if (port_.read(chunk, n) != transport::SerialIo::kDone) return;
          std::span<const std::uint8_t> rest(chunk.data(), n);
          while (!rest.empty()) {
            rest = rest.subspan(splitter_.feed(rest));
            BoardFrame frame;
            while (splitter_.next(frame)) frames.push_back(frame);
          }
        },
        [&] { return frames.size() >= count; }, timeout);
    return frames;
  }
  std::vector<BoardMotorState> states(const BoardFrame& frame) const {
    std::array<BoardMotorState, 32> out{};
    const std::size_t count = decode_board_states(frame.command, frame.bytes(), scaling_, out);
    return {out.begin(), out.begin() + static_cast<std::ptrdiff_t>(count)};
  }

 private:
  transport::SerialPort port_;
  BoardFrameSplitter splitter_;
  std::array<MotorScaling, kMaxMotorId + 1> scaling_{};
};

class HighTorqueBoardTest : public HighTorqueSimTest {
 protected:
  void SetUp() override { start_board(); }
  /// A board port of motors 1–3, given function version `function` as the host's start-up does.
  void start_board(std::vector<std::string> extra = {}, std::optional<BoardFunction> function = BoardFunction::kV5) {
    start({HighTorqueSimProcess::board("1-3")}, std::move(extra));
    host_ = std::make_unique<BoardHost>(sim_->bus_path(0));
    auto opened = host_->open();
    ASSERT_TRUE(opened) << opened.error().message;
    if (!function) return;
    host_->send(BoardCommand::kSetFunctionVersion, std::array<std::uint8_t, 1>{static_cast<std::uint8_t>(*function)});
    const auto echo = host_->receive(1);
    ASSERT_EQ(echo.size(), 1U);
    ASSERT_EQ(echo[0].command, BoardCommand::kSetFunctionVersion);
    ASSERT_EQ(echo[0].payload[0], static_cast<std::uint8_t>(*function));
  }
  std::unique_ptr<BoardHost> host_;
};

TEST_F(HighTorqueBoardTest, MitSlotsMoveTheMotorsAndTheBoardAnswersEveryState) {
  std::vector<BlockSlot> slots;
  for (int id = 1; id <= 3; ++id) slots.push_back(BlockSlot{.motor = id, .command = mit(0.2 * id, 10, 1)});
  host_->send_slots(BoardCommand::kPositionVelocityTorqueKpKd, slots);
  const auto answer = host_->receive(1);
  ASSERT_EQ(answer.size(), 1U);
  EXPECT_EQ(answer[0].command, BoardCommand::kMotorState2);
  const auto states = host_->states(answer[0]);
  ASSERT_EQ(states.size(), 3U);
  for (std::size_t i = 0; i < states.size(); ++i) {
    EXPECT_EQ(states[i].motor, static_cast<int>(i) + 1);
    EXPECT_EQ(states[i].mode, static_cast<std::uint8_t>(Mode::kMit));
    EXPECT_EQ(states[i].fault, 0);
  }
  ASSERT_TRUE(wait_until([] {}, [&] { return std::abs(motor(3)["position_rad"].get<double>() - 0.6) < 0.01; }, 3s));
  EXPECT_NEAR(motor(3)["kp"].get<double>(), 10, 0.1);
  const auto bus = sim_->state()["buses"][0];
  EXPECT_EQ(bus["kind"], "board");
  EXPECT_EQ(bus["frames_received"], 2);  // the function version, then the slots
  EXPECT_EQ(bus["frames_sent"], 2);
}

TEST_F(HighTorqueBoardTest, APacketWithABadCrcIsIgnored) {
  std::vector<std::uint8_t> packet(kBoardHeaderSize + kMaxBoardPayload);
  const std::array<BlockSlot, 1> slots{BlockSlot{.motor = 1, .command = mit(0.5, 10, 1)}};
  std::array<MotorScaling, kMaxMotorId + 1> scaling{};
  scaling.fill(MotorScaling{.torque_per_unit = kBoardTorqueUnit, .torque_offset_nm = 0, .gain_factor = 1});
  BoardSlotBuffer buffer(1);
  const std::span<const std::uint8_t> payload =
      buffer.update(BoardCommand::kPositionVelocityTorqueKpKd, slots, scaling);
  ASSERT_FALSE(payload.empty());
  const std::size_t total = encode_board_frame(BoardCommand::kPositionVelocityTorqueKpKd, payload, packet);
  packet.resize(total);
  packet.back() ^= 0xFF;  // the payload no longer matches its CRC-16
  host_->send_bytes(packet);
  EXPECT_TRUE(host_->receive(1, 150ms).empty());
  EXPECT_EQ(motor(1)["mode"], "stop");
  EXPECT_EQ(sim_->state()["buses"][0]["bad_frames"], 1);
  host_->send(BoardCommand::kMotorState2, std::array<std::uint8_t, 1>{0x7F});
  EXPECT_EQ(host_->receive(1).size(), 1U) << "the next good packet is served";
}

TEST_F(HighTorqueBoardTest, TimeoutBrakesTheMotorsAndTheirStateSaysSo) {
  const std::array<std::uint8_t, 6> timeout{0, 0, 100, 0, 0, 0};  // LE16 ms per motor: motor 2 only
  host_->send(BoardCommand::kTimeout, timeout);
  const std::array<BlockSlot, 1> slots{BlockSlot{.motor = 2, .command = mit(0, 0, 1)}};
  host_->send_slots(BoardCommand::kPositionVelocityTorqueKpKd, slots);
  ASSERT_EQ(host_->receive(1).size(), 1U);
  ASSERT_TRUE(wait_until([] {}, [&] { return motor(2)["fault"] == kTimeoutFault; }, 1s));
  EXPECT_EQ(motor(2)["mode"], "brake");
  host_->send(BoardCommand::kMotorState2, std::array<std::uint8_t, 1>{0x7F});
  const auto answer = host_->receive(1);
  ASSERT_EQ(answer.size(), 1U);
  const auto states = host_->states(answer[0]);
  ASSERT_EQ(states.size(), 3U);
  EXPECT_EQ(states[1].fault, kTimeoutFault);
  EXPECT_EQ(states[1].mode, static_cast<std::uint8_t>(Mode::kBrake));
  EXPECT_EQ(motor(1)["fault"], 0) << "motor 1's slot disarmed its timeout";
}

// The board's side of the SDK's start-up (robot.cc, canport.cc): 0x05 answers the board's
// firmware, 0x0E restarts its CAN-FD controllers from 4.1 on, 0x0B reports each motor's
// firmware, 0x0C sets the function version that decides what the board accepts.
TEST_F(HighTorqueBoardTest, StartUpPacketsAnswerAsTheBoardDoes) {
  start_board({"--board-firmware", "4.1", "--board-motor-firmware", "4.4.6", "--board-motor-firmware", "2:4.2.3"},
              std::nullopt);
  host_->send(BoardCommand::kSetMotorCount, std::array<std::uint8_t, 1>{3});
  auto answer = host_->receive(1);
  ASSERT_EQ(answer.size(), 1U);
  const std::optional<BoardFirmware> firmware = decode_board_firmware(answer[0].bytes());
  ASSERT_TRUE(firmware);
  EXPECT_EQ(firmware->tenths(), 41);
  host_->send(BoardCommand::kFdcanReset, std::array<std::uint8_t, 1>{0});
  host_->send(BoardCommand::kVersion, std::array<std::uint8_t, 1>{0x7F});
  answer = host_->receive(1);
  ASSERT_EQ(answer.size(), 1U);
  std::array<FirmwareVersion, 3> versions{};
  ASSERT_EQ(decode_board_versions(answer[0].bytes(), versions), 3U);
  EXPECT_EQ(versions[0].patch, 6);
  EXPECT_EQ(versions[1].minor, 2);
  EXPECT_EQ(versions[1].patch, 3);
  EXPECT_EQ(sim_->state()["buses"][0]["fdcan_resets"], 1);
  EXPECT_EQ(sim_->state()["buses"][0]["function_version"], 1);
  // Before the host sets function version 5, 0xB0 is ignored; at 4, 0x93 and 0x0A are served.
  const std::array<BlockSlot, 1> slots{BlockSlot{.motor = 1, .command = mit(0.3, 10, 1)}};
  host_->send_slots(BoardCommand::kPositionVelocityTorqueKpKd, slots);
  EXPECT_TRUE(host_->receive(1, 150ms).empty());
  host_->send(BoardCommand::kSetFunctionVersion, std::array<std::uint8_t, 1>{4});
  answer = host_->receive(1);
  ASSERT_EQ(answer.size(), 1U);
  EXPECT_EQ(answer[0].payload[0], 4);
  host_->send_slots(BoardCommand::kPositionVelocityTorqueKpKdV1, slots);
  answer = host_->receive(1);
  ASSERT_EQ(answer.size(), 1U);
  EXPECT_EQ(answer[0].command, BoardCommand::kMotorState2);
  ASSERT_TRUE(wait_until([] {}, [&] { return std::abs(motor(1)["position_rad"].get<double>() - 0.3) < 0.01; }, 3s));
  EXPECT_EQ(sim_->state()["buses"][0]["bad_frames"], 1);  // the early 0xB0
}

TEST_F(HighTorqueBoardTest, BoardsBeforeFirmware41DoNotKnowTheFdcanReset) {
  start_board({"--board-firmware", "4.0"}, BoardFunction::kV2);
  host_->send(BoardCommand::kFdcanReset, std::array<std::uint8_t, 1>{0});
  // Function version 2: states without mode and fault (0x06); 0x0A is ignored.
  host_->send(BoardCommand::kMotorState2, std::array<std::uint8_t, 1>{0x7F});
  host_->send(BoardCommand::kMotorState, std::array<std::uint8_t, 1>{0x7F});
  const auto answer = host_->receive(1);
  ASSERT_EQ(answer.size(), 1U);
  EXPECT_EQ(answer[0].command, BoardCommand::kMotorState);
  ASSERT_TRUE(wait_until([] {}, [&] { return sim_->state()["buses"][0]["bad_frames"] == 2; }, 1s));
  EXPECT_EQ(sim_->state()["buses"][0]["fdcan_resets"], 0);
}

TEST_F(HighTorqueBoardTest, RunToZeroDrivesTheMotorsBackToZero) {
  const std::array<BlockSlot, 1> slots{BlockSlot{.motor = 1, .command = mit(0.4, 10, 1)}};
  host_->send_slots(BoardCommand::kPositionVelocityTorqueKpKd, slots);
  ASSERT_TRUE(wait_until([] {}, [&] { return std::abs(motor(1)["position_rad"].get<double>() - 0.4) < 0.01; }, 3s));
  host_->send(BoardCommand::kRunToZero, std::array<std::uint8_t, 1>{0x7F});
  ASSERT_TRUE(wait_until([] {}, [&] { return std::abs(motor(1)["position_rad"].get<double>()) < 0.01; }, 3s));
  EXPECT_EQ(motor(1)["mode"], "position");
}

TEST_F(HighTorqueBoardTest, VersionAndStopAdminCommands) {
  host_->send(BoardCommand::kVersion, std::array<std::uint8_t, 1>{0});
  const auto versions = host_->receive(1);
  ASSERT_EQ(versions.size(), 1U);
  EXPECT_EQ(versions[0].command, BoardCommand::kVersion);
  ASSERT_EQ(versions[0].length, 12U);  // [id, major, minor, patch] × 3
  EXPECT_EQ(versions[0].payload[0], 1);
  EXPECT_EQ(versions[0].payload[1], 4);  // the board motors' default firmware 4.4.6
  EXPECT_EQ(versions[0].payload[2], 4);
  EXPECT_EQ(versions[0].payload[3], 6);
  host_->send(BoardCommand::kBrake, std::array<std::uint8_t, 1>{2});  // motor 2 only
  ASSERT_TRUE(wait_until([] {}, [&] { return motor(2)["mode"] == "brake"; }, 500ms));
  EXPECT_EQ(motor(1)["mode"], "stop");
}

TEST_F(HighTorqueBoardTest, DisconnectRemovesThePtyAndItComesBack) {
  control({{"op", "disconnect"}, {"bus", 0}, {"for_ms", 200}});
  ASSERT_TRUE(wait_until([] {}, [&] { return sim_->state()["buses"][0]["open"] == true; }, 2s));
  host_ = std::make_unique<BoardHost>(sim_->bus_path(0));
  ASSERT_TRUE(host_->open());
  host_->send(BoardCommand::kMotorState2, std::array<std::uint8_t, 1>{0x7F});
  EXPECT_EQ(host_->receive(1).size(), 1U);
}

// ---- The command line ----------------------------------------------------------------------

TEST(HighTorqueSimCommandLine, BadOptionsExitWith2) {
  const std::string sim = HighTorqueSimProcess::executable();
  const std::string path = HighTorqueSimProcess::unique_path("hightorque-bad");
  for (const std::vector<std::string>& arguments :
       std::vector<std::vector<std::string>>{{},
                                             {"--bus", path + ":0-3"},
                                             {"--bus", path + ":7-2"},
                                             {"--bus", path + ":1,1"},
                                             {"--bus", path},
                                             {"--bus", path + ":1", "--firmware", "1.2"},
                                             {"--board", path + ":1", "--board-firmware", "4"},
                                             {"--board", path + ":1", "--board-motor-firmware", "0:4.4.6"},
                                             {"--bus", path + ":1", "--bus", path + ":2"},
                                             {"--bus", path + ":1", "--torque-max", "-1"},
                                             {"--bus", path + ":1", "--no-such-option"}}) {
    std::string line;
    for (const std::string& argument : arguments) line += argument + " ";
    EXPECT_EQ(testing::run_to_exit(sim, arguments), 2) << line;
  }
}

TEST(HighTorqueSimCommandLine, ExitsCleanlyOnSigterm) {
  HighTorqueSimProcess sim({HighTorqueSimProcess::standin("1"), HighTorqueSimProcess::board("2")}, {"--quiet"});
  EXPECT_EQ(sim.terminate(), 0);
}

}  // namespace
}  // namespace robotd::hightorque
