#include "robotd_fixture.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

namespace robotd::testing {

void RobotdTest::start_robotd(const nlohmann::json& config, std::vector<std::string> environment) {
  start_robotd(config, std::move(environment), client_options(domain_.id()));
}

void RobotdTest::start_robotd(const nlohmann::json& config, std::vector<std::string> environment,
                              const ClientOptions& options) {
  robotd_ =
      std::make_unique<RobotdProcess>(config.is_null() ? sim_arm_config(domain_.id()) : config, std::move(environment));
  auto client = Client::connect(options);
  ASSERT_TRUE(client) << client.error().message;
  client_.emplace(std::move(client.value()));
  ASSERT_TRUE(robotd_->wait_ready(*client_)) << "robotd did not become ready:\n" << robotd_->log();
}

void RobotdTest::TearDown() {
  client_.reset();
  if (robotd_ && HasFailure()) std::cerr << "---- robotd log ----\n" << robotd_->log() << "--------------------\n";
  robotd_.reset();
}

Client RobotdTest::make_client(const std::string& node_name) {
  auto client = Client::connect(client_options(domain_.id(), node_name));
  EXPECT_TRUE(client) << client.error().message;
  return std::move(client.value());
}

DeviceStatus RobotdTest::device_status(const std::string& device) {
  // A sample robotd wrote after this call: a reader that has just matched may still be handed one
  // written before it (seen under load), and counters read from it would seem to go back.
  const std::int64_t asked_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  for (;;) {
    auto status = client_->next_device_status(device, std::chrono::seconds(3));
    EXPECT_TRUE(status) << status.error().message;
    if (!status) return DeviceStatus{};
    if (status.value().header.stamp.to_ns() >= asked_ns) return status.value();
    if (std::chrono::steady_clock::now() > deadline) {
      ADD_FAILURE() << "no /device_status sample of '" << device << "' written after it was asked for";
      return status.value();
    }
  }
}

double max_error(const JointState& state, const std::vector<float>& target) {
  double worst = 0;
  for (std::size_t j = 0; j < target.size(); ++j) worst = std::max(worst, std::fabs(state.position[j] - target[j]));
  return worst;
}

JointState RobotdTest::joint_state(const std::string& device) {
  auto state = client_->next_joint_state(device, std::chrono::seconds(3));
  EXPECT_TRUE(state) << state.error().message;
  return state ? state.value() : JointState{};
}

nlohmann::json RobotdTest::sim_state(const std::string& device) {
  auto state = client_->device_call(device, "state");
  EXPECT_TRUE(state) << state.error().message;
  return state ? nlohmann::json::parse(state.value()) : nlohmann::json::object();
}

nlohmann::json RobotdTest::sim_joints(const std::string& device) { return sim_state(device)["joints"]; }

bool RobotdTest::wait_for_joints(const std::function<bool(const JointState&)>& predicate,
                                 std::chrono::milliseconds timeout, const std::string& device) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    auto state = client_->next_joint_state(device, std::chrono::seconds(1));
    if (state && predicate(state.value())) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

DeviceStatus RobotdTest::wait_for_state(const std::string& device, DeviceState state,
                                        std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  DeviceStatus status = device_status(device);
  while (status.state != state && std::chrono::steady_clock::now() < deadline) status = device_status(device);
  return status;
}

nlohmann::json RobotdTest::vendor_device(const std::string& driver, const nlohmann::json& params) {
  return {{"name", driver},
          {"driver", driver},
          {"rate_hz", 1000},
          {"realtime", "prefer"},
          {"safe_behavior", "KEEP"},
          {"shutdown_behavior", "KEEP"},
          {"reconnect_interval_ms", 200},
          {"params", params}};
}

void RobotdTest::start_with_device(const nlohmann::json& device, bool with_sim_arm,
                                   std::vector<std::string> environment) {
  nlohmann::json config = sim_arm_config(domain_.id());
  if (with_sim_arm) {
    config["devices"].push_back(device);
  } else {
    config["devices"] = nlohmann::json::array({device});
  }
  start_robotd(config, std::move(environment));
}

Session RobotdTest::acquire_device(const std::string& device, std::vector<std::int32_t> motors, ControlMode mode,
                                   std::chrono::milliseconds timeout) {
  SessionRequest request;
  request.device = device;
  request.motor_ids = std::move(motors);
  request.mode = mode;
  request.on_timeout = Behavior::kKeep;
  request.timeout = timeout;
  auto session = client().request_control(request);
  EXPECT_TRUE(session) << session.error().message;
  return std::move(session.value());
}

nlohmann::json RobotdTest::call_device(const std::string& device, const std::string& op, const nlohmann::json& args) {
  auto reply = client().device_call(device, op, args.dump());
  EXPECT_TRUE(reply) << op << ": " << reply.error().message;
  return reply ? nlohmann::json::parse(reply.value()) : nlohmann::json();
}

}  // namespace robotd::testing
