// robotd-imu-sim as a host sees it: a process behind a pseudo-terminal, read with
// transport::SerialPort and the Yesense codec, steered through its control channel; its
// command line and its exit.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fcntl.h>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include <gtest/gtest.h>

#include "imu_sim_process.hpp"
#include "robotd/imu/yesense_codec.hpp"
#include "robotd/transport/serial_port.hpp"

namespace robotd::imu {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;
using testing::ImuSimProcess;
using Clock = std::chrono::steady_clock;

constexpr double kGravity = 9.80665;

/// Opens the emulator's pty and collects decoded readings for `window`.
std::vector<ImuReading> read_for(const std::string& device, std::chrono::milliseconds window,
                                 yesense::FrameSplitter* splitter_out = nullptr) {
  transport::SerialPort port(transport::SerialConfig{.device = device, .baud = 460'800});
  auto opened = port.open();
  EXPECT_TRUE(opened) << opened.error().message;
  std::vector<ImuReading> readings;
  yesense::FrameSplitter splitter;
  std::array<std::uint8_t, 1024> bytes{};
  const auto deadline = Clock::now() + window;
  while (Clock::now() < deadline) {
    std::size_t count = 0;
    if (port.read(bytes, count) != transport::SerialIo::kDone) {
      std::this_thread::sleep_for(1ms);
      continue;
    }
    std::span<const std::uint8_t> input(bytes.data(), count);
    yesense::Frame frame;
    while (splitter.next(input, frame)) {
      ImuReading reading;
      EXPECT_EQ(yesense::decode(frame.sequence, frame.payload, reading), yesense::DecodeStatus::kOk);
      readings.push_back(reading);
    }
  }
  if (splitter_out != nullptr) *splitter_out = splitter;
  return readings;
}

int run_to_exit(const std::vector<std::string>& arguments) {
  return testing::run_to_exit(ImuSimProcess::executable(), arguments);
}

TEST(ImuSim, StreamsValidFramesAtItsRate) {
  ImuSimProcess sim({}, {"--rate-hz", "100", "--quiet"});
  yesense::FrameSplitter splitter;
  const auto readings = read_for(sim.pty_path(), 1000ms, &splitter);
  ASSERT_GT(readings.size(), 85U);
  EXPECT_LT(readings.size(), 115U);
  EXPECT_EQ(splitter.counters().checksum_errors, 0U);
  for (std::size_t i = 1; i < readings.size(); ++i) {
    EXPECT_EQ(readings[i].sequence, readings[i - 1].sequence + 1);
    // On an absolute 10 ms schedule: a late frame is followed by an early one.
    const std::uint32_t step_us = readings[i].sample_time_us - readings[i - 1].sample_time_us;
    EXPECT_GT(step_us, 0U);
    EXPECT_LT(step_us, 50'000U);
  }
  const double mean_step_us = static_cast<double>(readings.back().sample_time_us - readings.front().sample_time_us) /
                              static_cast<double>(readings.size() - 1);
  EXPECT_NEAR(mean_step_us, 10'000.0, 1'000.0);
  for (const ImuReading& reading : readings) {
    ASSERT_TRUE(reading.has_orientation && reading.has_angular_velocity && reading.has_linear_acceleration &&
                reading.has_euler && reading.has_temperature && reading.has_sample_time);
    // The documented sway: roll ±0.05, pitch ±0.03, yaw ±0.02 rad about level.
    EXPECT_LE(std::abs(reading.euler_rad.roll), 0.05 + 1e-6);
    EXPECT_LE(std::abs(reading.euler_rad.pitch), 0.03 + 1e-6);
    EXPECT_LE(std::abs(reading.euler_rad.yaw), 0.02 + 1e-6);
    const auto& a = reading.linear_acceleration_m_s2;
    EXPECT_NEAR(std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), kGravity, 1e-5);
    EXPECT_LE(std::abs(reading.angular_velocity_rad_s[0]), 2 * M_PI * 0.5 * 0.05 + 2 * M_PI * 0.1 * 0.02 + 1e-5);
  }
  const json state = sim.control({{"op", "state"}});
  EXPECT_TRUE(state.value("swaying", false));
  EXPECT_GE(state.value("frames_sent", 0), static_cast<int>(readings.size()));
}

TEST(ImuSim, HoldsASetOrientationAndSwaysAgain) {
  ImuSimProcess sim({}, {"--quiet"});
  ASSERT_TRUE(sim.control({{"op", "set_orientation"}, {"roll_rad", -0.5}, {"pitch_rad", 0.25}, {"yaw_rad", 3.0}})
                  .value("ok", false));
  json state = sim.control({{"op", "state"}});
  EXPECT_FALSE(state.value("swaying", true));
  EXPECT_DOUBLE_EQ(state["orientation"].value("roll_rad", 0.0), -0.5);
  const auto held = read_for(sim.pty_path(), 200ms);
  ASSERT_FALSE(held.empty());
  EXPECT_NEAR(held.back().euler_rad.yaw, 3.0, 1e-6);
  ASSERT_TRUE(sim.control({{"op", "sway"}}).value("ok", false));
  state = sim.control({{"op", "state"}});
  EXPECT_TRUE(state.value("swaying", false));
  const auto swaying = read_for(sim.pty_path(), 300ms);
  ASSERT_FALSE(swaying.empty());
  EXPECT_NEAR(swaying.back().euler_rad.roll, -0.5, 0.05 + 1e-6);  // about the held orientation
}

TEST(ImuSim, ControlRequestsAreChecked) {
  ImuSimProcess sim({}, {"--quiet"});
  json reply = sim.control({{"op", "set_orientation"}, {"roll_rad", 0.1}, {"pitch_rad", 2.0}, {"yaw_rad", 0}});
  EXPECT_FALSE(reply.value("ok", true));
  EXPECT_NE(reply.value("error", "").find("pitch_rad"), std::string::npos) << reply.dump();
  reply = sim.control({{"op", "set_orientation"}, {"roll_rad", 0.1}});
  EXPECT_FALSE(reply.value("ok", true));
  reply = sim.control({{"op", "garbage"}, {"count", 0}});
  EXPECT_FALSE(reply.value("ok", true));
  reply = sim.control({{"op", "pause"}, {"for_ms", 10}, {"extra", 1}});
  EXPECT_FALSE(reply.value("ok", true));
  reply = sim.control({{"op", "fly"}});
  EXPECT_FALSE(reply.value("ok", true));
  EXPECT_NE(reply.value("error", "").find("state, set_orientation"), std::string::npos) << reply.dump();
}

TEST(ImuSim, GarbageAndCorruptFramesReachTheHost) {
  ImuSimProcess sim({}, {"--quiet"});
  ASSERT_TRUE(sim.control({{"op", "garbage"}, {"count", 500}}).value("ok", false));
  ASSERT_TRUE(sim.control({{"op", "corrupt"}, {"count", 3}}).value("ok", false));
  yesense::FrameSplitter splitter;
  const auto readings = read_for(sim.pty_path(), 400ms, &splitter);
  EXPECT_GT(readings.size(), 50U);
  EXPECT_GE(splitter.counters().checksum_errors, 3U);
  EXPECT_GE(splitter.counters().bytes_discarded, 400U);
  const json state = sim.control({{"op", "state"}});
  EXPECT_EQ(state.value("garbage_sent", 0), 500);
  EXPECT_EQ(state.value("frames_corrupted", 0), 3);
}

TEST(ImuSim, SigtermEndsItCleanly) {
  ImuSimProcess sim({}, {"--quiet"});
  const std::string pty = sim.pty_path();
  EXPECT_EQ(sim.terminate(), 0);
  EXPECT_NE(access(pty.c_str(), F_OK), 0) << "the pty symlink is removed at exit";
}

TEST(ImuSim, BadOptionsExitWithTwo) {
  const std::string pty = testing::SimProcess::unique_path("imu-bad", "");
  EXPECT_EQ(run_to_exit({}), 2) << "no --pty";
  EXPECT_EQ(run_to_exit({"--pty", pty, "--rate-hz", "0"}), 2);
  EXPECT_EQ(run_to_exit({"--pty", pty, "--rate-hz", "fast"}), 2);
  EXPECT_EQ(run_to_exit({"--pty", pty, "--bogus"}), 2);
  const std::string file = testing::SimProcess::unique_path("imu-file", "");
  const int fd = ::open(file.c_str(), O_CREAT | O_WRONLY, 0600);
  ASSERT_GE(fd, 0);
  ::close(fd);
  EXPECT_EQ(run_to_exit({"--pty", file, "--quiet"}), 2) << "a regular file is not replaced";
  unlink(file.c_str());
  EXPECT_EQ(run_to_exit({"--help"}), 0);
}

}  // namespace
}  // namespace robotd::imu
