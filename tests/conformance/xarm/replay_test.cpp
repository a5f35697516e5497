// The recorded requests of the xArm SDK's session sent again, in order, to a fresh robotd-xarm-sim
// over its real command port, and each reply compared with the recorded one byte for byte; the
// rich report packets a fresh simulator sends compared with the recorded ones.
//
// The SDK's session waited for each motion to end, polling while the arm or the gripper moved.
// The replay sends each request once the simulator is at rest instead (no timing), so two values
// read during motion are masked, and everything else in their frames is still compared:
//   - get_state (13) recorded as 1 (moving): its state byte;
//   - the gripper's status register (124, function 3, address 0x0000) recorded as moving: its value.
#include <chrono>
#include <stdexcept>
#include <string>
#include <sys/socket.h>
#include <thread>

#include <gtest/gtest.h>

#include "conformance_report.hpp"
#include "robotd/transport/ip_socket.hpp"
#include "transcript.hpp"
#include "vector_file.hpp"
#include "xarm_sim_process.hpp"

namespace robotd::conformance::xarm {
namespace {

using namespace std::chrono_literals;
using robotd::testing::XarmSimProcess;
using robotd::xarm::Bytes;
using robotd::xarm::Frame;
using robotd::xarm::Register;

constexpr std::uint8_t kMoving = 1;
constexpr std::size_t kStatusByte = 7;                           // header (6) + register
constexpr std::size_t kGripperValueFirstByte = kStatusByte + 5;  // host, device, function, count
constexpr auto kRestTimeout = 10s;
constexpr auto kReplyTimeout = 3s;

std::uint8_t reg_of(Register reg) { return static_cast<std::uint8_t>(reg); }

/// The byte offsets of `exchange`'s recorded reply that depend on when it was read.
std::vector<std::size_t> time_dependent_bytes(const Exchange& exchange) {
  const Frame& request = exchange.request_frame;
  const Bytes& reply = exchange.reply;
  if (request.reg == reg_of(Register::kGetState) && reply.size() > kStatusByte + 1 &&
      reply[kStatusByte + 1] == kMoving) {
    return {kStatusByte + 1};
  }
  const auto modbus = robotd::xarm::parse_tool_modbus_request(request.body);
  const bool status_read = request.reg == reg_of(Register::kToolModbus) && modbus &&
                           modbus.value().function == robotd::xarm::kModbusReadHolding &&
                           modbus.value().address == static_cast<std::uint16_t>(robotd::xarm::GripperRegister::kStatus);
  if (status_read && reply.size() >= kGripperValueFirstByte + 2 && reply[kGripperValueFirstByte + 1] == kMoving) {
    return {kGripperValueFirstByte, kGripperValueFirstByte + 1};
  }
  return {};
}

class CommandPort {
 public:
  explicit CommandPort(std::uint16_t port) {
    auto connected = transport::connect_tcp(transport::Endpoint{"127.0.0.1", port}, 2000ms);
    if (!connected) throw std::runtime_error("cannot connect to the simulator: " + connected.error().message);
    socket_ = std::move(connected).value();
  }

  void send(const Bytes& bytes) {
    std::size_t sent = 0;
    while (sent < bytes.size()) {
      const ssize_t n = ::send(socket_.fd(), bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) throw std::runtime_error("the simulator closed the command port");
      sent += static_cast<std::size_t>(n);
    }
  }

  /// The reply to `transaction_id` (motion-feedback frames are skipped), as its bytes.
  Bytes reply_to(std::uint16_t transaction_id) {
    const auto deadline = std::chrono::steady_clock::now() + kReplyTimeout;
    while (std::chrono::steady_clock::now() < deadline) {
      auto next = frames_.next();
      if (!next) throw std::runtime_error(next.error().message);
      if (next.value()) {
        const Frame& frame = *next.value();
        if (!robotd::xarm::is_motion_feedback(frame) && frame.transaction_id == transaction_id) {
          return robotd::xarm::encode_frame(frame);
        }
        continue;
      }
      if (!transport::wait_readable(socket_.fd(), 50ms)) continue;
      std::array<std::uint8_t, 4096> buffer{};
      const ssize_t n = ::recv(socket_.fd(), buffer.data(), buffer.size(), 0);
      if (n <= 0) throw std::runtime_error("the simulator closed the command port");
      frames_.append(robotd::xarm::ByteView(buffer.data(), static_cast<std::size_t>(n)));
    }
    throw std::runtime_error("no reply to transaction " + std::to_string(transaction_id));
  }

 private:
  transport::Socket socket_;
  robotd::xarm::FrameSplitter frames_;
};

/// Waits until nothing moves: no queued or running motion, the gripper stopped (or gripping).
void wait_at_rest(const XarmSimProcess& sim) {
  const auto deadline = std::chrono::steady_clock::now() + kRestTimeout;
  while (std::chrono::steady_clock::now() < deadline) {
    const nlohmann::json state = sim.control({{"op", "state"}});
    const bool gripper_still = state.at("gripper").at("status") != robotd::xarm::kGripperMoving;
    if (state.at("state") != kMoving && state.at("cmdnum") == 0 && gripper_still) return;
    std::this_thread::sleep_for(5ms);
  }
  throw std::runtime_error("the simulator did not come to rest within 10 s");
}

std::vector<std::string> simulator_arguments(std::uint16_t rich_port) {
  const Transcript& recorded = transcript();
  return {"--quiet",
          "--model",
          recorded.model,
          "--firmware",
          recorded.firmware,
          "--rich-report-port",
          std::to_string(rich_port)};
}

TEST(XarmReplay, EveryRecordedReplyComesBackFromAFreshSimulator) {
  XarmSimProcess sim(simulator_arguments(XarmSimProcess::free_port()));
  CommandPort port(sim.port());
  for (const Exchange& exchange : transcript().exchanges) {
    wait_at_rest(sim);
    for (const nlohmann::json& control : exchange.control_before) {
      ASSERT_EQ(sim.control(control).at("ok"), true) << control.dump();
    }
    port.send(exchange.request);
    Bytes replayed = port.reply_to(exchange.request_frame.transaction_id);
    Bytes recorded = exchange.reply;
    for (const std::size_t offset : time_dependent_bytes(exchange)) {
      if (offset < replayed.size()) replayed[offset] = 0;
      recorded[offset] = 0;
    }
    const bool same = replayed == recorded;
    record("replay", same ? Outcome::passed : Outcome::failed);
    EXPECT_TRUE(same) << "step " << exchange.step << ", request " << hex_text(exchange.request) << "\n  recorded "
                      << hex_text(exchange.reply) << "\n  replayed " << hex_text(replayed);
  }
}

/// A report port's packets from its first: what a client that just connected reads.
std::vector<Bytes> first_packets(std::uint16_t port, std::size_t count) {
  auto connected = transport::connect_tcp(transport::Endpoint{"127.0.0.1", port}, 2000ms);
  if (!connected) throw std::runtime_error("cannot connect to the rich report port: " + connected.error().message);
  robotd::xarm::ReportSplitter splitter;
  std::vector<Bytes> packets;
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (packets.size() < count && std::chrono::steady_clock::now() < deadline) {
    auto next = splitter.next();
    if (!next) throw std::runtime_error(next.error().message);
    if (next.value()) {
      packets.push_back(*next.value());
      continue;
    }
    if (!transport::wait_readable(connected.value().fd(), 50ms)) continue;
    std::array<std::uint8_t, 4096> buffer{};
    const ssize_t n = ::recv(connected.value().fd(), buffer.data(), buffer.size(), 0);
    if (n <= 0) break;
    splitter.append(robotd::xarm::ByteView(buffer.data(), static_cast<std::size_t>(n)));
  }
  return packets;
}

TEST(XarmReplay, TheRichReportAtConnectIsTheRecordedOne) {
  const std::uint16_t rich_port = XarmSimProcess::free_port();
  XarmSimProcess sim(simulator_arguments(rich_port));
  for (const ReportConnection& connection : transcript().reports) {
    ASSERT_EQ(connection.kind, robotd::xarm::ReportKind::kRich) << "the SDK's default report is the rich one";
    const std::vector<Bytes> packets = first_packets(rich_port, connection.packets.size());
    ASSERT_EQ(packets.size(), connection.packets.size());
    for (std::size_t i = 0; i < packets.size(); ++i) {
      const bool same = packets[i] == connection.packets[i];
      record("reports", same ? Outcome::passed : Outcome::failed);
      EXPECT_TRUE(same) << "rich packet " << i << "\n  recorded " << hex_text(connection.packets[i]) << "\n  replayed "
                        << hex_text(packets[i]);
    }
  }
}

}  // namespace
}  // namespace robotd::conformance::xarm
