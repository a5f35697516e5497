// The CAN transports over real file descriptors: the stand-in (driver ⇄ simulator bus over a
// unix seqpacket socket), and SocketCAN where the kernel has it.
#include "robotd/transport/can_transport.hpp"

#include <chrono>
#include <string>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>

#include <gtest/gtest.h>

#include "robotd/transport/can_bus.hpp"
#include "robotd/transport/can_interface_check.hpp"

namespace robotd::transport {
namespace {

using namespace std::chrono_literals;

std::string socket_path() { return "/tmp/robotd-can-test-" + std::to_string(getpid()) + ".sock"; }

CanLinkConfig standin(const std::string& path) {
  CanLinkConfig config;
  config.kind = CanLinkConfig::Kind::kStandIn;
  config.path = path;
  return config;
}

/// Polls `receive` until it returns something other than kNone (or a second passes).
template <class Link>
CanIo receive_within(Link& link, CanMessage& out) {
  const auto deadline = std::chrono::steady_clock::now() + 1s;
  CanIo result = CanIo::kNone;
  while (result == CanIo::kNone && std::chrono::steady_clock::now() < deadline) {
    result = link.receive(out);
    if (result == CanIo::kNone) std::this_thread::sleep_for(1ms);
  }
  return result;
}

class StandInTest : public ::testing::Test {
 protected:
  void SetUp() override {
    bus_ = make_can_bus(standin(path_));
    ASSERT_TRUE(bus_->open());
    driver_ = make_can_transport(standin(path_));
    ASSERT_TRUE(driver_->open());
  }
  std::string path_ = socket_path();
  std::unique_ptr<CanTransport> bus_;
  std::unique_ptr<CanTransport> driver_;
};

TEST_F(StandInTest, ClassicFrameTravelsBothWaysUnchanged) {
  const std::uint8_t bytes[] = {0x01, 0x02, 0x03, 0xFE, 0xFF, 0x00, 0x7F, 0x80};
  ASSERT_EQ(driver_->send(classic_frame(0x155, bytes)), CanIo::kDone);
  CanMessage received;
  ASSERT_EQ(receive_within(*bus_, received), CanIo::kDone);
  EXPECT_EQ(received.id, 0x155U);
  EXPECT_FALSE(received.extended);
  EXPECT_FALSE(received.fd);
  ASSERT_EQ(received.length, 8);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(received.data[i], bytes[i]);

  ASSERT_EQ(bus_->send(classic_frame(0x2A5, bytes)), CanIo::kDone);
  ASSERT_EQ(receive_within(*driver_, received), CanIo::kDone);
  EXPECT_EQ(received.id, 0x2A5U);
}

TEST_F(StandInTest, ExtendedFdFrameKeepsIdentifierLengthAndBitrateSwitch) {
  CanMessage message;
  message.id = 0x18001U;
  message.extended = true;
  message.fd = true;
  message.bitrate_switch = true;
  message.length = 48;
  for (std::uint8_t i = 0; i < 48; ++i) message.data[i] = i;
  ASSERT_EQ(driver_->send(message), CanIo::kDone);
  CanMessage received;
  ASSERT_EQ(receive_within(*bus_, received), CanIo::kDone);
  EXPECT_EQ(received.id, 0x18001U);
  EXPECT_TRUE(received.extended);
  EXPECT_TRUE(received.fd);
  EXPECT_TRUE(received.bitrate_switch);
  EXPECT_EQ(received.length, 48);
  EXPECT_EQ(received.data[47], 47);
}

TEST_F(StandInTest, ErrorFramesArriveAsBusErrorsWithTheirMeaning) {
  CanMessage error;
  error.error_frame = true;
  error.id = 0x40;  // CAN_ERR_BUSOFF
  error.length = 8;
  ASSERT_EQ(bus_->send(error), CanIo::kDone);
  CanMessage received;
  ASSERT_EQ(receive_within(*driver_, received), CanIo::kBusError);
  EXPECT_EQ(describe_bus_error(received), "bus off");
}

TEST_F(StandInTest, BusForwardsOneNodesFramesToTheOthers) {
  auto monitor = make_can_transport(standin(path_));
  ASSERT_TRUE(monitor->open());
  CanMessage ignored;
  (void)bus_->receive(ignored);  // the bus accepts the monitor as a node
  const std::uint8_t bytes[] = {0xAA};
  ASSERT_EQ(driver_->send(classic_frame(0x471, bytes)), CanIo::kDone);
  CanMessage at_bus;
  ASSERT_EQ(receive_within(*bus_, at_bus), CanIo::kDone);
  CanMessage at_monitor;
  ASSERT_EQ(receive_within(*monitor, at_monitor), CanIo::kDone);
  EXPECT_EQ(at_monitor.id, 0x471U);
}

TEST_F(StandInTest, DriverSeesTheLinkCloseWhenTheSimulatorGoes) {
  bus_->close();
  CanMessage received;
  EXPECT_EQ(receive_within(*driver_, received), CanIo::kClosed);
  const std::uint8_t bytes[] = {1};
  EXPECT_EQ(driver_->send(classic_frame(0x150, bytes)), CanIo::kClosed);
}

TEST_F(StandInTest, DriverReconnectsWhenTheSimulatorReturns) {
  bus_->close();
  bus_ = make_can_bus(standin(path_));
  ASSERT_TRUE(bus_->open());
  ASSERT_TRUE(driver_->open());
  const std::uint8_t bytes[] = {9};
  ASSERT_EQ(driver_->send(classic_frame(0x151, bytes)), CanIo::kDone);
  CanMessage received;
  EXPECT_EQ(receive_within(*bus_, received), CanIo::kDone);
}

TEST(StandIn, OpeningWithoutASimulatorSaysSo) {
  auto driver = make_can_transport(standin("/tmp/robotd-no-such-bus.sock"));
  auto opened = driver->open();
  ASSERT_FALSE(opened);
  EXPECT_NE(opened.error().message.find("is the simulator running"), std::string::npos) << opened.error().message;
}

TEST(StandIn, ReceiveIsNonBlocking) {
  const std::string path = socket_path() + ".idle";
  auto bus = make_can_bus(standin(path));
  ASSERT_TRUE(bus->open());
  auto driver = make_can_transport(standin(path));
  ASSERT_TRUE(driver->open());
  CanMessage out;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(driver->receive(out), CanIo::kNone);
  EXPECT_LT(std::chrono::steady_clock::now() - start, 5ms);
}

bool kernel_has_socketcan() {
  const int sock = socket(PF_CAN, SOCK_RAW, 1 /* CAN_RAW */);
  if (sock < 0) return false;
  close(sock);
  return true;
}

TEST(SocketCan, MissingInterfaceOrMissingAfCanIsExplained) {
  CanLinkConfig config;
  config.interface = "robotdcan9";
  auto transport = make_can_transport(config);
  auto opened = transport->open();
  ASSERT_FALSE(opened);
  if (kernel_has_socketcan()) {
    EXPECT_NE(opened.error().message.find("no CAN interface 'robotdcan9'"), std::string::npos)
        << opened.error().message;
  } else {
    EXPECT_NE(opened.error().message.find("this kernel has no SocketCAN"), std::string::npos) << opened.error().message;
  }
}

TEST(SocketCan, VcanRoundTripWhenTheKernelHasIt) {
  if (!kernel_has_socketcan() || access("/sys/class/net/vcan0", F_OK) != 0) {
    GTEST_SKIP() << "no AF_CAN or no vcan0 on this machine (modprobe vcan; ip link add vcan0 type vcan; "
                    "ip link set vcan0 up)";
  }
  CanLinkConfig config;
  config.interface = "vcan0";
  auto a = make_can_transport(config);
  auto b = make_can_bus(config);
  ASSERT_TRUE(a->open());
  ASSERT_TRUE(b->open());
  const std::uint8_t bytes[] = {1, 2, 3};
  ASSERT_EQ(a->send(classic_frame(0x123, bytes)), CanIo::kDone);
  CanMessage received;
  ASSERT_EQ(receive_within(*b, received), CanIo::kDone);
  EXPECT_EQ(received.id, 0x123U);
}

TEST(CanLinkConfig, ReadsEitherTransportAndNamesBadKeys) {
  std::vector<std::string> errors;
  const nlohmann::json standin_json = {{"transport", "standin"}, {"path", "/tmp/x.sock"}};
  JsonReader reader(standin_json, "can", errors);
  const CanLinkConfig config = read_can_link(reader);
  EXPECT_TRUE(errors.empty());
  EXPECT_EQ(config.kind, CanLinkConfig::Kind::kStandIn);
  EXPECT_EQ(config.path, "/tmp/x.sock");

  const nlohmann::json bad = {{"transport", "carrier-pigeon"}, {"interfaec", "can0"}};
  JsonReader bad_reader(bad, "can", errors);
  (void)read_can_link(bad_reader);
  ASSERT_EQ(errors.size(), 2U);
  EXPECT_NE(errors[0].find("can.transport: expected one of"), std::string::npos) << errors[0];
  EXPECT_NE(errors[1].find("can.interfaec: unknown key"), std::string::npos) << errors[1];
}

// The judge_flag checks on interfaces every Linux machine has (no CAN hardware needed).
TEST(CanInterfaceCheck, SaysWhatIsWrongWithTheInterface) {
  const auto missing = check_can_interface("robotdcan9", 1'000'000);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::kNotAvailable);
  EXPECT_NE(missing.error().message.find("CAN interface robotdcan9 does not exist"), std::string::npos)
      << missing.error().message;

  const auto loopback = check_can_interface("lo", 1'000'000);
  ASSERT_FALSE(loopback);
  EXPECT_EQ(loopback.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(loopback.error().message.find("lo is not a CAN interface"), std::string::npos) << loopback.error().message;

  const auto injected = check_can_interface("can0; reboot", 1'000'000);
  ASSERT_FALSE(injected);
  EXPECT_NE(injected.error().message.find("is not an interface name"), std::string::npos) << injected.error().message;
}

}  // namespace
}  // namespace robotd::transport
