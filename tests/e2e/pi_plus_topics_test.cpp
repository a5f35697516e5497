// End to end: the PI Plus topics beside the control interface. robotd's joystick source fed
// recorded js_event records through a FIFO (/joy), the /yesense_imu/* topics of a simulated
// humanoid's IMU, and robotctl echo of /policy_data from a policy's publisher.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fcntl.h>
#include <linux/joystick.h>
#include <mutex>
#include <numbers>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

#include <gtest/gtest.h>

#include "dds/yesense_imu.hpp"
#include "joystick/joystick_mapper.hpp"
#include "robotd_fixture.hpp"
#include "sample_queue.hpp"
#include "wire/qos.hpp"
#include "wire/topic_io.hpp"
#include "wire/topics.hpp"

#ifndef ROBOTCTL_BINARY
#error "ROBOTCTL_BINARY must point at the robotctl executable under test"
#endif

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

constexpr std::int16_t kFull = 32767;

bool neutral(const Joy& joy) { return joystick::same_values(joy, Joy{}); }

class PiPlusTopicsTest : public RobotdTest {
 protected:
  void TearDown() override {
    RobotdTest::TearDown();
    if (!fifo_.empty()) std::remove(fifo_.c_str());
  }

  std::string make_fifo() {
    fifo_ = "/tmp/robotd-e2e-joy-" + std::to_string(getpid()) + "-" + std::to_string(domain_.id());
    std::remove(fifo_.c_str());
    EXPECT_EQ(mkfifo(fifo_.c_str(), 0600), 0);
    return fifo_;
  }

  /// Polls `reader` until a sample satisfies `predicate`.
  template <class T>
  std::optional<T> take_until(const wire::TopicReader<T>& reader, const std::function<bool(const T&)>& predicate,
                              std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::optional<T> found;
    while (!found && std::chrono::steady_clock::now() < deadline) {
      reader.take_each([&](T&& value, const dds_sample_info_t& /*info*/) {
        if (!found && predicate(value)) found = std::move(value);
      });
      if (!found) std::this_thread::sleep_for(5ms);
    }
    return found;
  }

  std::string fifo_;
};

TEST_F(PiPlusTopicsTest, JsEventsWrittenToTheJoystickDeviceArriveOnJoyAndItsUnplugGivesNeutral) {
  nlohmann::json config = sim_arm_config(domain_.id());
  config["joystick"] = {{"device", make_fifo()}, {"interface", "js"}, {"rate_hz", 20}, {"deadzone", 0.1}};
  start_robotd(config);
  SampleQueue<Joy> joys;
  const Subscription subscription = client().on_joy([&](const Joy& joy) { joys.offer(joy); });
  ASSERT_TRUE(joys.wait_for([this](const Joy& joy) { return joy.header.frame_id == fifo_; }, 5s))
      << "no /joy sample while the device is open";

  const int fd = open(fifo_.c_str(), O_WRONLY);
  ASSERT_GE(fd, 0);
  // What the kernel's js driver sends: the initial state (JS_EVENT_INIT), then changes.
  const std::vector<js_event> events = {
      {.time = 100, .value = 0, .type = JS_EVENT_AXIS | JS_EVENT_INIT, .number = 0},
      {.time = 100, .value = -kFull, .type = JS_EVENT_AXIS | JS_EVENT_INIT, .number = 2},  // LT released
      {.time = 100, .value = 0, .type = JS_EVENT_BUTTON | JS_EVENT_INIT, .number = 0},
      {.time = 150, .value = -kFull, .type = JS_EVENT_AXIS, .number = 1},  // left stick full up
      {.time = 160, .value = kFull, .type = JS_EVENT_AXIS, .number = 3},   // right stick full right
      {.time = 170, .value = 0, .type = JS_EVENT_AXIS, .number = 5},       // RT half way
      {.time = 180, .value = 1, .type = JS_EVENT_BUTTON, .number = 0},     // A
      {.time = 190, .value = 1, .type = JS_EVENT_BUTTON, .number = 8},     // guide
      {.time = 200, .value = -kFull, .type = JS_EVENT_AXIS, .number = 7},  // d-pad up
  };
  for (const js_event& event : events) {
    ASSERT_EQ(write(fd, &event, sizeof(event)), static_cast<ssize_t>(sizeof(event)));
  }
  const auto pushed = joys.wait_for([](const Joy& joy) { return joy.a == 1.0F && joy.dpad_vertical == 1.0F; }, 3s);
  ASSERT_TRUE(pushed) << "the events never showed on /joy";
  EXPECT_FLOAT_EQ(pushed->l_vertical, 1.0F);
  EXPECT_FLOAT_EQ(pushed->l_horizontal, 0.0F);
  EXPECT_FLOAT_EQ(pushed->r_horizontal, -1.0F);
  EXPECT_FLOAT_EQ(pushed->lt, 0.0F);
  EXPECT_NEAR(pushed->rt, (0.5 - 0.1) / 0.9, 1e-4);  // half way, past a 10 % dead zone
  EXPECT_FLOAT_EQ(pushed->center, 1.0F);
  EXPECT_FLOAT_EQ(pushed->b, 0.0F);

  close(fd);  // the controller goes away
  EXPECT_TRUE(joys.wait_for(neutral, 3s)) << "no neutral /joy after the device went away";
  EXPECT_NE(robotd_->log().find("joystick: lost " + fifo_), std::string::npos) << robotd_->log();
}

TEST_F(PiPlusTopicsTest, YesenseTopicsCarryTheHumanoidsImuInDegrees) {
  nlohmann::json config = sim_arm_config(domain_.id());
  nlohmann::json humanoid = config["devices"][0];
  humanoid["name"] = "humanoid";
  humanoid["joint_state_rate_hz"] = 100;
  humanoid["params"] = {{"joint_count", 23}, {"imu", true}, {"model", "test humanoid"}};
  config["devices"] = nlohmann::json::array({humanoid});
  start_robotd(config);
  call_device("humanoid", "set_imu",
              {{"rpy_deg", {10.0, -20.0, 30.0}},
               {"angular_velocity_rad_s", {0.1, -0.2, 0.3}},
               {"linear_acceleration_m_s2", {0.5, 0.0, 9.81}}});

  wire::DdsSettings settings;
  settings.domain_id = domain_.id();
  auto participant = wire::Participant::create(settings);
  ASSERT_TRUE(participant) << participant.error().message;
  const auto qos = wire::reliable_qos(10);  // PI Plus clients subscribe reliable
  auto rpy = wire::TopicReader<Vector3>::create(participant.value(), wire::kYesenseRpyTopic, qos.get());
  auto gyro = wire::TopicReader<Vector3>::create(participant.value(), wire::kYesenseGyroTopic, qos.get());
  auto acc = wire::TopicReader<Vector3>::create(participant.value(), wire::kYesenseAccTopic, qos.get());
  auto quat = wire::TopicReader<Quaternion>::create(participant.value(), wire::kYesenseQuatTopic, qos.get());
  auto yesense_imu = wire::TopicReader<Imu>::create(participant.value(), wire::kYesenseImuTopic, qos.get());
  ASSERT_TRUE(rpy && gyro && acc && quat && yesense_imu);

  SampleQueue<Imu> imus;
  const Subscription subscription = client().on_imu([&](const Imu& imu) { imus.offer(imu); });
  const auto imu = imus.wait_for([](const Imu& sample) { return sample.angular_velocity.x > 0.05; }, 5s);
  ASSERT_TRUE(imu) << "/imu never showed the IMU set on the simulator";
  const Vector3 expected_rpy = dds::rpy_degrees(imu->orientation);
  EXPECT_NEAR(expected_rpy.x, 10.0, 1e-6);

  const auto near = [](double a, double b) { return std::abs(a - b) < 1e-6; };
  const auto rpy_sample = take_until<Vector3>(
      rpy.value(), [&](const Vector3& v) { return near(v.x, expected_rpy.x); }, 5s);
  ASSERT_TRUE(rpy_sample) << "no /yesense_imu/rpy in degrees";
  EXPECT_NEAR(rpy_sample->x, 10.0, 1e-6);
  EXPECT_NEAR(rpy_sample->y, -20.0, 1e-6);
  EXPECT_NEAR(rpy_sample->z, 30.0, 1e-6);
  const double deg = 180.0 / std::numbers::pi;
  const auto gyro_sample = take_until<Vector3>(
      gyro.value(), [&](const Vector3& v) { return v.x > 1.0; }, 5s);
  ASSERT_TRUE(gyro_sample) << "no /yesense_imu/gyro in deg/s";
  EXPECT_NEAR(gyro_sample->x, 0.1 * deg, 1e-6);
  EXPECT_NEAR(gyro_sample->y, -0.2 * deg, 1e-6);
  EXPECT_NEAR(gyro_sample->z, 0.3 * deg, 1e-6);
  const auto acc_sample = take_until<Vector3>(
      acc.value(), [&](const Vector3& v) { return v.x > 0.4; }, 5s);
  ASSERT_TRUE(acc_sample);
  EXPECT_DOUBLE_EQ(acc_sample->z, 9.81);
  const auto quat_sample = take_until<Quaternion>(
      quat.value(), [&](const Quaternion& q) { return near(q.w, imu->orientation.w); }, 5s);
  ASSERT_TRUE(quat_sample);
  EXPECT_NEAR(quat_sample->x, imu->orientation.x, 1e-9);
  const auto imu_sample = take_until<Imu>(
      yesense_imu.value(), [&](const Imu& sample) { return sample.angular_velocity.x > 0.05; }, 5s);
  ASSERT_TRUE(imu_sample);
  EXPECT_EQ(imu_sample->header.frame_id, "humanoid");
  EXPECT_NEAR(imu_sample->angular_velocity.z, 0.3, 1e-9) << "/yesense_imu/imu is /imu: rad/s";
}

class PolicyDataTest : public PiPlusTopicsTest {
 protected:
  /// Publishes `samples` once `robotctl` has subscribed (its subscription matches the writer).
  void publish_when_matched(const std::vector<PolicyData>& samples) {
    auto publisher = client_->policy_data_publisher();
    ASSERT_TRUE(publisher) << publisher.error().message;
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (publisher.value().matched_subscribers() == 0 && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(10ms);
    }
    ASSERT_GT(publisher.value().matched_subscribers(), 0) << "robotctl never subscribed to /policy_data";
    for (const PolicyData& sample : samples) ASSERT_TRUE(publisher.value().publish(sample));
    std::this_thread::sleep_for(500ms);  // let robotctl take them before the writer goes
  }

  void SetUp() override {
    auto client = Client::connect(client_options(domain_.id(), "policy"));
    ASSERT_TRUE(client) << client.error().message;
    client_.emplace(std::move(client.value()));
  }

  std::vector<std::string> robotctl_arguments(std::vector<std::string> verb) const {
    std::vector<std::string> arguments{"--domain", std::to_string(domain_.id())};
    arguments.insert(arguments.end(), verb.begin(), verb.end());
    return arguments;
  }

  static PolicyData sample(const std::string& data_type, std::vector<double> data) {
    PolicyData out;
    out.header.stamp = Time{1700000000, 500};
    out.header.frame_id = "policy";
    out.data_type = data_type;
    out.data = std::move(data);
    return out;
  }
};

TEST_F(PolicyDataTest, RobotctlEchoJsonPrintsEachSampleAsOneLine) {
  ChildProcess echo(ROBOTCTL_BINARY, robotctl_arguments({"echo", "policy_data", "--json", "--count", "2"}));
  publish_when_matched({sample("obs", {0.5, -1.25, 3.0}), sample("action", {})});
  const auto first = echo.read_line(5s);
  const auto second = echo.read_line(5s);
  ASSERT_TRUE(first && second) << "robotctl printed nothing";
  const auto obs = nlohmann::json::parse(*first);
  EXPECT_EQ(obs["data_type"], "obs");
  EXPECT_EQ(obs["data"], nlohmann::json::parse("[0.5, -1.25, 3.0]"));
  EXPECT_EQ(obs["header"]["stamp"]["sec"], 1700000000);
  EXPECT_EQ(obs["header"]["frame_id"], "policy");
  EXPECT_EQ(nlohmann::json::parse(*second)["data_type"], "action");
}

TEST_F(PolicyDataTest, RobotctlEchoPrintsAReadableBlock) {
  ChildProcess echo(ROBOTCTL_BINARY, robotctl_arguments({"echo", "/policy_data", "--count", "1"}));
  publish_when_matched({sample("state_q", {0.1, 0.2})});
  const auto heading = echo.read_line(5s);
  const auto values = echo.read_line(5s);
  ASSERT_TRUE(heading && values);
  EXPECT_EQ(heading->rfind("policy_data  state_q  stamp 1700000000.000000", 0), 0U) << *heading;
  EXPECT_NE(values->find("2 values: 0.1 0.2"), std::string::npos) << *values;
}

}  // namespace
}  // namespace robotd::testing
