// GoogleTest fixture: a robotd process on a private DDS domain and a client connected to it.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "robotd/client.hpp"
#include "robotd_process.hpp"
#include "test_domain.hpp"

namespace robotd::testing {

/// The largest |position - target| over the target's joints.
double max_error(const JointState& state, const std::vector<float>& target);

class RobotdTest : public ::testing::Test {
 protected:
  /// Starts robotd with `config` (default: the test arm) and waits until it is ready.
  void start_robotd(const nlohmann::json& config = nullptr, std::vector<std::string> environment = {});
  /// The same, with client() connecting with `options` (e.g. a DDS Security identity).
  void start_robotd(const nlohmann::json& config, std::vector<std::string> environment, const ClientOptions& options);
  void TearDown() override;

  Client& client() { return *client_; }
  /// Another client on the same domain, e.g. a second user.
  Client make_client(const std::string& node_name);

  DeviceStatus device_status(const std::string& device = "arm");
  JointState joint_state(const std::string& device = "arm");
  /// The sim driver's own view (device_call "state").
  nlohmann::json sim_state(const std::string& device = "arm");
  /// sim_state()["joints"] as a value of its own: `for (auto& j : sim_state()["joints"])` would walk
  /// a member of a temporary destroyed before the loop starts.
  nlohmann::json sim_joints(const std::string& device = "arm");
  /// Waits until `predicate(joint_state)` holds; false on timeout.
  bool wait_for_joints(const std::function<bool(const JointState&)>& predicate, std::chrono::milliseconds timeout,
                       const std::string& device = "arm");
  /// The device's status once it is in `state`, or the last one seen after `timeout`.
  DeviceStatus wait_for_state(const std::string& device, DeviceState state,
                              std::chrono::milliseconds timeout = std::chrono::seconds(5));

  // Vendor drivers end to end: a device named after its driver, next to the test arm or alone.
  /// The device entry the vendor tests run: 1 kHz, KEEP on fault and shutdown, reconnecting
  /// every 200 ms, `params` for the driver.
  static nlohmann::json vendor_device(const std::string& driver, const nlohmann::json& params);
  /// Starts robotd with `device`, alone or (with_sim_arm) after the simulated arm "arm".
  void start_with_device(const nlohmann::json& device, bool with_sim_arm, std::vector<std::string> environment = {});
  /// A session on `device` that KEEPs on timeout; a test failure when refused.
  Session acquire_device(const std::string& device, std::vector<std::int32_t> motors = {},
                         ControlMode mode = ControlMode::kPosition,
                         std::chrono::milliseconds timeout = std::chrono::seconds(10));
  /// A device_call that must succeed: its JSON result (null, and a test failure, when refused).
  nlohmann::json call_device(const std::string& device, const std::string& op,
                             const nlohmann::json& args = nlohmann::json::object());

  TestDomain domain_;
  std::unique_ptr<RobotdProcess> robotd_;
  std::optional<Client> client_;
};

}  // namespace robotd::testing
