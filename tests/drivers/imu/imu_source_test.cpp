// The ImuSource drivers attach (robotd/imu/imu_source.hpp): its params, and the Yesense source
// against robotd-imu-sim over a pseudo-terminal — samples at the emulator's rate, the
// orientation it was told, link down on a pause or an unplug and back up by itself.
#include "robotd/imu/imu_source.hpp"

#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "imu_sim_process.hpp"
#include "robotd/driver/monotonic_clock.hpp"
#include "robotd/kinematics/rotation.hpp"

namespace robotd::imu {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;
using testing::ImuSimProcess;
using Clock = std::chrono::steady_clock;

constexpr double kStandardGravity = 9.80665;

/// Polls `condition` every 10 ms until it holds or `timeout` passed.
bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (Clock::now() < deadline) {
    if (condition()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return condition();
}

std::unique_ptr<ImuSource> source_on(const std::string& device, std::int64_t timeout_ms = 100) {
  auto made = make_imu_source(
      json{{"source", "yesense"}, {"serial", {{"device", device}, {"baud", 460'800}}}, {"timeout_ms", timeout_ms}},
      "imu");
  EXPECT_TRUE(made) << made.error().message;
  return made ? std::move(made).value() : nullptr;
}

bool link_is(const ImuSource& source, LinkState state) { return source.status().link == state; }

/// A running emulator and a started source on its pty, the link up.
class LiveImuSource : public ::testing::Test {
 protected:
  void bring_up(const std::vector<std::string>& sim_args = {"--quiet"}) {
    sim_.emplace(std::string(), sim_args);
    source_ = source_on(sim_->pty_path());
    ASSERT_NE(source_, nullptr);
    ASSERT_TRUE(source_->start());
    ASSERT_TRUE(eventually([&] { return link_is(*source_, LinkState::kUp); }, 3s)) << source_->status().error;
  }

  std::optional<ImuSimProcess> sim_;
  std::unique_ptr<ImuSource> source_;
};

TEST(ImuSourceParams, DefaultsToTheYesenseSettings) {
  std::vector<std::string> errors;
  const json params = {{"serial", {{"device", "/dev/ttyUSB3"}}}};
  JsonReader reader(params, "imu", errors);
  const ImuSourceConfig config = read_imu_source_config(reader);
  EXPECT_TRUE(errors.empty()) << join_errors(errors);
  EXPECT_EQ(config.source, "yesense");
  EXPECT_EQ(config.serial.device, "/dev/ttyUSB3");
  EXPECT_EQ(config.serial.baud, 460'800);
  EXPECT_EQ(config.timeout_ms, 100);
}

TEST(ImuSourceParams, ErrorsNameTheKey) {
  const auto made = make_imu_source(
      json{{"source", "xsens"}, {"serial", {{"baud", 123}}}, {"timeout_ms", 0}, {"rate", 5}}, "devices[0].params.imu");
  ASSERT_FALSE(made);
  EXPECT_EQ(made.error().code, ErrorCode::kInvalidArgument);
  const std::string& message = made.error().message;
  EXPECT_NE(message.find("devices[0].params.imu.source: expected one of \"yesense\""), std::string::npos) << message;
  EXPECT_NE(message.find("devices[0].params.imu.serial.device: missing"), std::string::npos) << message;
  EXPECT_NE(message.find("devices[0].params.imu.serial.baud: expected one of"), std::string::npos) << message;
  EXPECT_NE(message.find("devices[0].params.imu.timeout_ms"), std::string::npos) << message;
  EXPECT_NE(message.find("devices[0].params.imu.rate"), std::string::npos) << message;
  const auto no_serial = make_imu_source(json{{"source", "yesense"}}, "imu");
  ASSERT_FALSE(no_serial);
  EXPECT_NE(no_serial.error().message.find("imu.serial: missing"), std::string::npos) << no_serial.error().message;
  const auto not_object = make_imu_source(json::array(), "imu");
  ASSERT_FALSE(not_object);
}

TEST(ImuSource, StoppedSourceHasNoSample) {
  auto source = source_on("/tmp/robotd-imu-nowhere");
  ASSERT_NE(source, nullptr);
  driver::ImuSample sample;
  std::int64_t stamp = 0;
  EXPECT_FALSE(source->latest(sample, stamp));
  EXPECT_EQ(source->status().link, LinkState::kStopped);
  EXPECT_EQ(source->describe(), "yesense on /tmp/robotd-imu-nowhere");
  source->stop();  // safe when never started
}

TEST_F(LiveImuSource, SamplesArriveAtTheEmulatorsRate) {
  ASSERT_NO_FATAL_FAILURE(bring_up({"--rate-hz", "200", "--quiet"}));
  const std::uint64_t before = source_->status().samples;
  std::this_thread::sleep_for(2s);
  const ImuStatus status = source_->status();
  const double rate = static_cast<double>(status.samples - before) / 2.0;
  EXPECT_GT(rate, 170.0);
  EXPECT_LT(rate, 230.0);
  EXPECT_GT(status.rate_hz, 150.0);
  EXPECT_LT(status.rate_hz, 250.0);
  EXPECT_EQ(status.checksum_errors, 0U);
  EXPECT_EQ(status.malformed, 0U);
  EXPECT_EQ(status.sequence_gaps, 0U);
  ASSERT_TRUE(status.age_ms);
  EXPECT_LT(*status.age_ms, 100.0);
  EXPECT_EQ(status.content, "orientation, gyro, accel, euler, temperature, sample time");

  driver::ImuSample sample;
  std::int64_t stamp = 0;
  ASSERT_TRUE(source_->latest(sample, stamp));
  const std::int64_t now_ns = driver::monotonic_now_ns();
  EXPECT_LE(stamp, now_ns);
  EXPECT_LT(now_ns - stamp, 100'000'000);
  // Swaying gently about level: gravity dominates the specific force.
  const auto& a = sample.linear_acceleration_m_s2;
  EXPECT_NEAR(std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), kStandardGravity, 1e-3);
  EXPECT_GT(a[2], 9.7);

  const auto diagnostics = source_->diagnostics();
  ASSERT_GE(diagnostics.size(), 4U);
  EXPECT_EQ(diagnostics[0].first, "imu");
  EXPECT_NE(diagnostics[0].second.find("(up)"), std::string::npos) << diagnostics[0].second;
  EXPECT_EQ(diagnostics[1].first, "imu_frames");
  EXPECT_EQ(diagnostics[2].first, "imu_rate");
  EXPECT_EQ(diagnostics[3].first, "imu_age");
  source_->stop();
  EXPECT_FALSE(source_->latest(sample, stamp));
  EXPECT_EQ(source_->status().link, LinkState::kStopped);
}

TEST_F(LiveImuSource, OrientationFollowsSetOrientation) {
  ASSERT_NO_FATAL_FAILURE(bring_up());
  const double roll = 0.3;
  const double pitch = -0.2;
  const double yaw = 1.0;
  ASSERT_TRUE(sim_->control({{"op", "set_orientation"}, {"roll_rad", roll}, {"pitch_rad", pitch}, {"yaw_rad", yaw}})
                  .value("ok", false));
  ImuReading reading;
  std::int64_t stamp = 0;
  ASSERT_TRUE(eventually(
      [&] {
        return source_->latest_reading(reading, stamp) && std::abs(reading.euler_rad.roll - roll) < 1e-5 &&
               std::abs(reading.euler_rad.yaw - yaw) < 1e-5;
      },
      2s));
  EXPECT_NEAR(reading.euler_rad.pitch, pitch, 1e-5);
  const auto expected = kinematics::quaternion_xyzw_from_rpy({roll, pitch, yaw});
  double dot = 0;
  for (std::size_t i = 0; i < 4; ++i) dot += expected[i] * reading.orientation_xyzw[i];
  EXPECT_NEAR(std::abs(dot), 1.0, 1e-9);
  // Held still: no rotation; specific force is gravity in body axes.
  for (const double rate : reading.angular_velocity_rad_s) EXPECT_NEAR(rate, 0.0, 1e-6);
  EXPECT_NEAR(reading.linear_acceleration_m_s2[0], -kStandardGravity * std::sin(pitch), 1e-5);
  EXPECT_NEAR(reading.linear_acceleration_m_s2[1], kStandardGravity * std::sin(roll) * std::cos(pitch), 1e-5);
  EXPECT_NEAR(reading.linear_acceleration_m_s2[2], kStandardGravity * std::cos(roll) * std::cos(pitch), 1e-5);
  EXPECT_NEAR(reading.temperature_c, 36.5, 1e-9);
}

TEST_F(LiveImuSource, PauseSilencesTheLinkUntilFramesReturn) {
  ASSERT_NO_FATAL_FAILURE(bring_up());
  ASSERT_TRUE(sim_->control({{"op", "pause"}, {"for_ms", 800}}).value("ok", false));
  driver::ImuSample sample;
  std::int64_t stamp = 0;
  ASSERT_TRUE(eventually([&] { return link_is(*source_, LinkState::kSilent); }, 500ms));
  EXPECT_FALSE(source_->latest(sample, stamp));
  EXPECT_NE(source_->status().error.find("no valid frame"), std::string::npos) << source_->status().error;
  ASSERT_TRUE(eventually([&] { return link_is(*source_, LinkState::kUp); }, 2s));
  EXPECT_TRUE(source_->latest(sample, stamp));
  EXPECT_EQ(source_->status().opens, 1U);  // the line stayed open
}

TEST_F(LiveImuSource, UnpluggedLineIsDownAndComesBackByItself) {
  ASSERT_NO_FATAL_FAILURE(bring_up());
  // The emulator hangs its pty up and removes the symlink, as an unplugged USB adapter.
  ASSERT_TRUE(sim_->control({{"op", "disconnect"}, {"for_ms", 1500}}).value("ok", false));
  ASSERT_TRUE(eventually([&] { return link_is(*source_, LinkState::kDown); }, 1s));
  driver::ImuSample sample;
  std::int64_t stamp = 0;
  EXPECT_FALSE(source_->latest(sample, stamp));
  EXPECT_FALSE(source_->status().error.empty());
  // Back after 1.5 s (a new /dev/pts/N behind the same link); the source retries every second.
  ASSERT_TRUE(eventually([&] { return link_is(*source_, LinkState::kUp); }, 4s)) << source_->status().error;
  EXPECT_TRUE(source_->latest(sample, stamp));
  EXPECT_EQ(source_->status().opens, 2U);
}

TEST_F(LiveImuSource, KilledAndRestartedEmulator) {
  ASSERT_NO_FATAL_FAILURE(bring_up());
  sim_->kill_hard();
  ASSERT_TRUE(eventually([&] { return link_is(*source_, LinkState::kDown); }, 1s));
  sim_->restart();
  ASSERT_TRUE(eventually([&] { return link_is(*source_, LinkState::kUp); }, 4s)) << source_->status().error;
}

TEST(ImuSource, MissingDeviceIsRetriedUntilItAppears) {
  const std::string path = testing::SimProcess::unique_path("imu-late", "");
  auto source = source_on(path);
  ASSERT_NE(source, nullptr);
  ASSERT_TRUE(source->start());  // not there: not an error
  ASSERT_TRUE(eventually([&] { return link_is(*source, LinkState::kDown); }, 500ms));
  EXPECT_NE(source->status().error.find(path), std::string::npos) << source->status().error;
  ImuSimProcess sim(path, {"--quiet"});
  ASSERT_TRUE(eventually([&] { return link_is(*source, LinkState::kUp); }, 3s)) << source->status().error;
}

TEST_F(LiveImuSource, GarbageAndBadChecksumsAreCountedNotFatal) {
  ASSERT_NO_FATAL_FAILURE(bring_up());
  ASSERT_TRUE(sim_->control({{"op", "garbage"}, {"count", 3000}}).value("ok", false));
  ASSERT_TRUE(sim_->control({{"op", "corrupt"}, {"count", 5}}).value("ok", false));
  ASSERT_TRUE(eventually([&] { return source_->status().checksum_errors >= 5; }, 2s))
      << source_->status().checksum_errors;
  const std::uint64_t samples = source_->status().samples;
  ASSERT_TRUE(eventually([&] { return source_->status().samples > samples + 50; }, 2s));
  const ImuStatus status = source_->status();
  EXPECT_EQ(status.link, LinkState::kUp);
  EXPECT_GE(status.bytes_discarded, 1000U);
  EXPECT_GE(status.sequence_gaps, 1U);  // the corrupted frames' TIDs are missing
}

}  // namespace
}  // namespace robotd::imu
