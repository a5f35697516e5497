// GoogleTest fixture: a robotd process on a private DDS domain and a client connected to it.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "robotd/client.hpp"
#include "robotd_process.hpp"
#include "test_domain.hpp"

namespace robotd::testing {

class RobotdTest : public ::testing::Test {
 protected:
  /// Starts robotd with `config` (default: the test arm) and waits until it is ready.
  void start_robotd(const nlohmann::json& config = nullptr, std::vector<std::string> environment = {});
  void TearDown() override;

  Client& client() { return *client_; }
  /// Another client on the same domain, e.g. a second user.
  Client make_client(const std::string& node_name);

  DeviceStatus device_status(const std::string& device = "arm");
  JointState joint_state(const std::string& device = "arm");
  /// The sim driver's own view (device_call "state").
  nlohmann::json sim_state(const std::string& device = "arm");
  /// Waits until `predicate(joint_state)` holds; false on timeout.
  bool wait_for_joints(const std::function<bool(const JointState&)>& predicate, std::chrono::milliseconds timeout,
                       const std::string& device = "arm");

  TestDomain domain_;
  std::unique_ptr<RobotdProcess> robotd_;
  std::optional<Client> client_;
};

}  // namespace robotd::testing
