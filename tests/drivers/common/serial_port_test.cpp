// The serial transport over real file descriptors: a pseudo-terminal pair stands in for the
// USB serial device, the way the PAROL6 simulator offers it to the driver.
#include "robotd/transport/serial_port.hpp"

#include <array>
#include <cerrno>
#include <chrono>
#include <fcntl.h>
#include <string>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include <gtest/gtest.h>

namespace robotd::transport {
namespace {

using namespace std::chrono_literals;

std::string link_path(const std::string& stem) {
  static int counter = 0;
  return "/tmp/robotd-serial-test-" + stem + "-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
}

SerialConfig config_for(const std::string& device, int baud = 3'000'000) {
  SerialConfig config;
  config.device = device;
  config.baud = baud;
  return config;
}

/// Reads from `port` until `expected` bytes came, the line closed, or a second passed.
SerialIo read_bytes(SerialPort& port, std::vector<std::uint8_t>& out, std::size_t expected) {
  const auto deadline = std::chrono::steady_clock::now() + 1s;
  std::array<std::uint8_t, 256> chunk{};
  SerialIo result = SerialIo::kNone;
  while (out.size() < expected && std::chrono::steady_clock::now() < deadline) {
    std::size_t count = 0;
    result = port.read(chunk, count);
    if (result == SerialIo::kClosed) return result;
    if (result == SerialIo::kDone) {
      out.insert(out.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(count));
    } else {
      std::this_thread::sleep_for(1ms);
    }
  }
  return result;
}

/// Reads from the pty's master until `expected` bytes came or a second passed.
std::vector<std::uint8_t> read_master(const PseudoTerminal& pty, std::size_t expected,
                                      std::chrono::milliseconds timeout = 1s) {
  std::vector<std::uint8_t> out;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::array<std::uint8_t, 256> chunk{};
  while (out.size() < expected && std::chrono::steady_clock::now() < deadline) {
    const ssize_t n = ::read(pty.fd(), chunk.data(), chunk.size());
    if (n > 0) {
      out.insert(out.end(), chunk.begin(), chunk.begin() + n);
    } else {
      std::this_thread::sleep_for(1ms);
    }
  }
  return out;
}

class PtyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto opened = pty_.open(link_);
    ASSERT_TRUE(opened) << opened.error().message;
    auto port_opened = port_.open();
    ASSERT_TRUE(port_opened) << port_opened.error().message;
  }
  void TearDown() override {
    port_.close();
    pty_.close();
    unlink(link_.c_str());
  }

  std::string link_ = link_path("pty");
  PseudoTerminal pty_;
  SerialPort port_{config_for(link_)};
};

TEST_F(PtyTest, BytesTravelBothWaysUnchanged) {
  // Every byte value, including the ones a cooked terminal would translate (CR, LF, XON, ^C).
  std::vector<std::uint8_t> all(256);
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<std::uint8_t>(i);
  std::size_t written = 0;
  ASSERT_EQ(port_.write(all, written), SerialIo::kDone);
  ASSERT_EQ(written, all.size());
  EXPECT_EQ(read_master(pty_, all.size()), all);

  ASSERT_EQ(::write(pty_.fd(), all.data(), all.size()), static_cast<ssize_t>(all.size()));
  std::vector<std::uint8_t> received;
  read_bytes(port_, received, all.size());
  EXPECT_EQ(received, all) << "raw mode: no echo, no translation, no flow control";
  EXPECT_TRUE(read_master(pty_, 1, 50ms).empty()) << "nothing echoed back";
}

TEST_F(PtyTest, ReadWithNothingWaitingIsNone) {
  std::array<std::uint8_t, 16> buffer{};
  std::size_t count = 99;
  EXPECT_EQ(port_.read(buffer, count), SerialIo::kNone);
  EXPECT_EQ(count, 0U);
}

TEST_F(PtyTest, HostSeesClosedWhenThePseudoTerminalCloses) {
  pty_.close();
  std::vector<std::uint8_t> received;
  EXPECT_EQ(read_bytes(port_, received, 1), SerialIo::kClosed);
  const std::array<std::uint8_t, 4> bytes{1, 2, 3, 4};
  std::size_t written = 0;
  EXPECT_EQ(port_.write(bytes, written), SerialIo::kClosed);
}

TEST_F(PtyTest, MasterReadsEioOnceNoProcessHoldsTheDeviceOpen) {
  // What the simulator takes as "no host connected".
  std::array<std::uint8_t, 16> buffer{};
  errno = 0;
  EXPECT_EQ(::read(pty_.fd(), buffer.data(), buffer.size()), -1);
  EXPECT_EQ(errno, EAGAIN) << "a host is there, silent";
  port_.close();
  errno = 0;
  EXPECT_EQ(::read(pty_.fd(), buffer.data(), buffer.size()), -1);
  EXPECT_EQ(errno, EIO);
  ASSERT_TRUE(port_.open()) << "the device end can be opened again";
  errno = 0;
  EXPECT_EQ(::read(pty_.fd(), buffer.data(), buffer.size()), -1);
  EXPECT_EQ(errno, EAGAIN);
}

TEST_F(PtyTest, ASecondOpenOfTheSameLineIsRefused) {
  SerialPort second(config_for(link_));
  auto opened = second.open();
  ASSERT_FALSE(opened);
  EXPECT_NE(opened.error().message.find("in use"), std::string::npos) << opened.error().message;
  port_.close();
  EXPECT_TRUE(second.open()) << "free again once the first closed it";
}

TEST_F(PtyTest, FlushDropsWhatIsWaiting) {
  const std::array<std::uint8_t, 3> bytes{0xFF, 0xFF, 0xFF};
  ASSERT_EQ(::write(pty_.fd(), bytes.data(), bytes.size()), 3);
  std::this_thread::sleep_for(20ms);
  port_.flush();
  std::array<std::uint8_t, 16> buffer{};
  std::size_t count = 0;
  EXPECT_EQ(port_.read(buffer, count), SerialIo::kNone);
}

TEST_F(PtyTest, AFullBufferIsNoneNotClosed) {
  const std::array<std::uint8_t, 64> bytes{};
  SerialIo result = SerialIo::kDone;
  for (int i = 0; i < 100'000 && result == SerialIo::kDone; ++i) {
    std::size_t written = 0;
    result = port_.write(bytes, written);
  }
  EXPECT_EQ(result, SerialIo::kNone) << "the master never reads: the kernel buffer fills";
}

TEST_F(PtyTest, TheLinkPointsAtTheDeviceAndGoesWithIt) {
  std::array<char, 128> target{};
  const ssize_t length = readlink(link_.c_str(), target.data(), target.size() - 1);
  ASSERT_GT(length, 0);
  EXPECT_EQ(std::string(target.data(), static_cast<std::size_t>(length)), pty_.device_path());
  EXPECT_EQ(pty_.device_path().rfind("/dev/pts/", 0), 0U) << pty_.device_path();
  pty_.close();
  struct stat info {};
  EXPECT_NE(lstat(link_.c_str(), &info), 0) << "close removes the symlink";
}

TEST(PseudoTerminal, MasterReadsEioBeforeAnyHostOpenedTheDevice) {
  PseudoTerminal pty;
  ASSERT_TRUE(pty.open(""));
  std::array<std::uint8_t, 16> buffer{};
  errno = 0;
  EXPECT_EQ(::read(pty.fd(), buffer.data(), buffer.size()), -1);
  EXPECT_EQ(errno, EIO) << "no host connected, the same as after one left";
}

TEST(PseudoTerminal, AStaleLinkIsReplaced) {
  const std::string link = link_path("stale");
  ASSERT_EQ(symlink("/dev/pts/nonexistent", link.c_str()), 0);
  PseudoTerminal pty;
  auto opened = pty.open(link);
  ASSERT_TRUE(opened) << opened.error().message;
  SerialPort port(config_for(link));
  EXPECT_TRUE(port.open());
}

TEST(PseudoTerminal, ARegularFileAtTheLinkPathIsNotReplaced) {
  const std::string path = link_path("file");
  const int fd = ::open(path.c_str(), O_CREAT | O_WRONLY | O_CLOEXEC, 0600);
  ASSERT_GE(fd, 0);
  ::close(fd);
  PseudoTerminal pty;
  auto opened = pty.open(path);
  ASSERT_FALSE(opened);
  EXPECT_NE(opened.error().message.find("not a symlink"), std::string::npos) << opened.error().message;
  unlink(path.c_str());
}

TEST(PseudoTerminal, WithoutALinkTheDevicePathIsOpened) {
  PseudoTerminal pty;
  ASSERT_TRUE(pty.open(""));
  SerialPort port(config_for(pty.device_path()));
  auto opened = port.open();
  EXPECT_TRUE(opened) << opened.error().message;
}

// --- open errors -------------------------------------------------------------------------------

TEST(SerialPortOpen, AMissingDeviceSaysToCheckTheCable) {
  SerialPort port(config_for("/dev/ttyACM-robotd-missing"));
  auto opened = port.open();
  ASSERT_FALSE(opened);
  EXPECT_NE(opened.error().message.find("/dev/ttyACM-robotd-missing does not exist"), std::string::npos);
  EXPECT_NE(opened.error().message.find("plugged in"), std::string::npos) << opened.error().message;
  EXPECT_FALSE(port.is_open());
}

TEST(SerialPortOpen, ANonTerminalIsRefused) {
  SerialPort port(config_for("/dev/null"));
  auto opened = port.open();
  ASSERT_FALSE(opened);
  EXPECT_NE(opened.error().message.find("not a terminal"), std::string::npos) << opened.error().message;
  EXPECT_FALSE(port.is_open());
}

TEST(SerialPortOpen, AnUnsupportedBaudListsTheSupportedOnes) {
  SerialPort port(config_for("/dev/ttyACM0", 12345));
  auto opened = port.open();
  ASSERT_FALSE(opened);
  EXPECT_NE(opened.error().message.find("12345"), std::string::npos) << opened.error().message;
  EXPECT_NE(opened.error().message.find("115200"), std::string::npos) << opened.error().message;
  EXPECT_NE(opened.error().message.find("3000000"), std::string::npos) << opened.error().message;
}

TEST(SerialPortOpen, AClosedPortReportsClosed) {
  SerialPort port(config_for("/dev/ttyACM0"));
  std::array<std::uint8_t, 4> buffer{};
  std::size_t count = 0;
  EXPECT_EQ(port.read(buffer, count), SerialIo::kClosed);
  EXPECT_EQ(port.write(buffer, count), SerialIo::kClosed);
  port.flush();  // harmless
  EXPECT_EQ(port.describe(), "serial /dev/ttyACM0");
}

// --- config ------------------------------------------------------------------------------------

struct Parsed {
  SerialConfig config;
  std::vector<std::string> errors;
};

Parsed parse(const nlohmann::json& params) {
  Parsed parsed;
  JsonReader reader(params, "serial", parsed.errors);
  parsed.config = read_serial_link(reader);
  return parsed;
}

std::string joined(const std::vector<std::string>& errors) { return join_errors(errors); }

TEST(ReadSerialLink, ReadsDeviceAndBaud) {
  const Parsed parsed = parse({{"device", "/dev/ttyACM1"}, {"baud", 115200}});
  EXPECT_TRUE(parsed.errors.empty()) << joined(parsed.errors);
  EXPECT_EQ(parsed.config.device, "/dev/ttyACM1");
  EXPECT_EQ(parsed.config.baud, 115200);
}

TEST(ReadSerialLink, BaudDefaultsTo3000000) {
  const Parsed parsed = parse({{"device", "/tmp/parol6.tty"}});
  EXPECT_TRUE(parsed.errors.empty()) << joined(parsed.errors);
  EXPECT_EQ(parsed.config.baud, 3'000'000);
}

TEST(ReadSerialLink, TheDeviceIsRequired) {
  const Parsed parsed = parse(nlohmann::json::object());
  ASSERT_EQ(parsed.errors.size(), 1U);
  EXPECT_NE(parsed.errors[0].find("serial.device"), std::string::npos) << parsed.errors[0];
  EXPECT_NE(parsed.errors[0].find("missing"), std::string::npos) << parsed.errors[0];
}

TEST(ReadSerialLink, RefusesBadValues) {
  EXPECT_NE(joined(parse({{"device", ""}}).errors).find("must not be empty"), std::string::npos);
  EXPECT_NE(joined(parse({{"device", 5}}).errors).find("serial.device"), std::string::npos);
  const std::string baud = joined(parse({{"device", "/dev/ttyACM0"}, {"baud", 12345}}).errors);
  EXPECT_NE(baud.find("serial.baud"), std::string::npos) << baud;
  EXPECT_NE(baud.find("3000000"), std::string::npos) << baud;
  EXPECT_NE(joined(parse({{"device", "/dev/ttyACM0"}, {"baud", "fast"}}).errors).find("serial.baud"),
            std::string::npos);
  EXPECT_NE(joined(parse({{"device", "/dev/ttyACM0"}, {"bauds", 9600}}).errors).find("bauds"), std::string::npos)
      << "a typo is an error";
}

}  // namespace
}  // namespace robotd::transport
