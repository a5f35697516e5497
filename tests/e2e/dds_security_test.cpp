// End to end through a real robotd process with DDS Security on (issue 9): only a participant
// whose certificate may publish rt/control_command moves a motor. The deployment's material is
// made by scripts/make-dds-security; a second run of it is a CA robotd does not trust.
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "robotd_fixture.hpp"
#include "security_materials.hpp"

#if !defined(ROBOTCTL_BINARY) || !defined(COMMAND_STREAMER)
#error "ROBOTCTL_BINARY and COMMAND_STREAMER must point at the executables under test"
#endif

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

SessionRequest keep_arm_request() {
  SessionRequest request;
  request.device = "arm";
  request.on_timeout = Behavior::kKeep;
  request.timeout = 10s;
  return request;
}

class DdsSecurityTest : public RobotdTest {
 protected:
  /// robotd with the deployment's robotd identity; client() is its operator. Cyclone applies
  /// DDS Security per domain and process, so every other identity runs in a process of its own.
  void start_secure_robotd() {
    nlohmann::json config = sim_arm_config(domain_.id());
    config["dds"]["security"] = deployment_.config("robotd");
    ClientOptions options = client_options(domain_.id(), "operator");
    options.security = deployment_.files("operator");
    const auto start = std::chrono::steady_clock::now();
    start_robotd(config, {}, options);
    std::printf("[ measured ] make-dds-security %.2f s; secure robotd started and answered the operator in %.2f s\n",
                deployment_.seconds_to_make(), seconds_since(start));
  }

  /// `program` with `arguments` and this test's --domain, run as participant `name` of
  /// `materials` (its ROBOTD_DDS_SECURITY_* variables set), or without DDS Security when
  /// `materials` is null. Its stdout and stderr are read as one.
  std::unique_ptr<ChildProcess> run_as(const SecurityMaterials* materials, const std::string& name,
                                       const std::string& program, const std::vector<std::string>& arguments) {
    std::vector<std::string> command{"-c", "exec \"$@\" 2>&1", "sh", "env"};
    if (materials != nullptr) {
      const nlohmann::json files = materials->config(name);
      for (const auto& [key, path] : files.items()) {
        std::string variable = "ROBOTD_DDS_SECURITY_" + key;
        for (char& c : variable) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        command.push_back(variable + "=" + path.get<std::string>());
      }
    }
    command.insert(command.end(), {program, "--domain", std::to_string(domain_.id())});
    command.insert(command.end(), arguments.begin(), arguments.end());
    return std::make_unique<ChildProcess>("/bin/sh", command);
  }

  /// Lines `child` prints until one is `wanted` (the empty string then) or it has printed nothing
  /// for `timeout`: what it printed instead. A client with another CA's identity gets Cyclone's
  /// handshake failures on the same stream, before or after its own line.
  static std::optional<std::string> lines_before(ChildProcess& child, const std::string& wanted,
                                                 std::chrono::seconds timeout) {
    std::string others;
    while (auto line = child.read_line(timeout)) {
      if (*line == wanted) return std::nullopt;
      others += *line + "\n";
    }
    return others;
  }

  /// Everything `child` prints until it exits.
  static std::string output_of(ChildProcess& child) {
    std::string text;
    while (auto line = child.read_line(10s)) text += *line + "\n";
    return text;
  }

  SecurityMaterials deployment_;
};

TEST_F(DdsSecurityTest, OperatorRequestsControlAndMovesTheArm) {
  start_secure_robotd();
  auto session = client().request_control(keep_arm_request());
  ASSERT_TRUE(session) << session.error().message;

  const std::vector<float> target{0.5F, -0.3F, 0.4F, 0.2F, -0.4F, 0.3F};
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(wait_for_joints(
      [&](const JointState& state) {
        (void)session.value().send_positions(target);
        return max_error(state, target) < 0.01;
      },
      5s))
      << "the operator's commands did not move the arm";
  std::printf("[ measured ] the operator's move arrived in %.2f s\n", seconds_since(start));
  const DeviceStatus status = device_status();
  EXPECT_GT(status.commands.accepted, 0U);
  EXPECT_EQ(status.commands.rejected_total(), 0U);
}

// The viewer, through robotctl and the environment its dds-security.env sets: it sees the
// arm, but neither requests control nor gets a command out, even in a live session's name.
TEST_F(DdsSecurityTest, ViewerReadsJointStatesButMayNotCommand) {
  start_secure_robotd();
  auto session = client().request_control(keep_arm_request());
  ASSERT_TRUE(session) << session.error().message;

  const auto start = std::chrono::steady_clock::now();
  const std::string echo =
      output_of(*run_as(&deployment_, "viewer", ROBOTCTL_BINARY, {"echo", "joint_states", "--count", "1"}));
  std::printf(
      "[ measured ] robotctl as a late viewer printed its first /joint_states after %.2f s "
      "(process start, handshake, first sample)\n",
      seconds_since(start));
  EXPECT_NE(echo.find("joint6"), std::string::npos) << echo;
  const std::string devices = output_of(*run_as(&deployment_, "viewer", ROBOTCTL_BINARY, {"devices"}));
  EXPECT_NE(devices.find("arm"), std::string::npos) << "list_devices is read-only; the viewer may call it:\n"
                                                    << devices;

  const std::string move =
      output_of(*run_as(&deployment_, "viewer", ROBOTCTL_BINARY, {"move", "arm", "--to", "0.3,0,0,0,0,0"}));
  EXPECT_NE(move.find("not allowed by DDS Security"), std::string::npos) << move;
  const std::string stolen = output_of(
      *run_as(&deployment_, "viewer", COMMAND_STREAMER, {"--uuid", session.value().uuid(), "--position", "1.0"}));
  EXPECT_EQ(stolen.rfind("failed ", 0), 0U) << stolen;
  EXPECT_NE(stolen.find("rt/control_command: not allowed by DDS Security"), std::string::npos) << stolen;

  EXPECT_EQ(device_status().commands.received, 0U);
  for (const auto& joint : sim_joints()) EXPECT_EQ(joint["command"], "none") << joint.dump();
}

// Neither a participant without DDS Security nor one whose CA robotd does not trust gets a
// command to a motor, even in the name of a live session whose uuid it has learned.
TEST_F(DdsSecurityTest, ParticipantsOutsideTheDeploymentNeverReachAMotor) {
  start_secure_robotd();
  auto session = client().request_control(keep_arm_request());
  ASSERT_TRUE(session) << session.error().message;
  const JointState before = joint_state();

  // Their own DDS lets them write: each prints "streaming" once its first command is out.
  const SecurityMaterials other_ca;
  const std::vector<std::string> stream{"--uuid", session.value().uuid(), "--position", "1.0"};
  const auto unsecured = run_as(nullptr, "", COMMAND_STREAMER, stream);
  const auto outsider = run_as(&other_ca, "operator", COMMAND_STREAMER, stream);
  EXPECT_EQ(lines_before(*unsecured, "streaming", 10s), std::nullopt);
  EXPECT_EQ(lines_before(*outsider, "streaming", 10s), std::nullopt);
  const std::string devices =
      output_of(*run_as(&other_ca, "operator", ROBOTCTL_BINARY, {"--timeout-ms", "1000", "devices"}));
  EXPECT_NE(devices.find("no robotd answers"), std::string::npos) << devices;
  std::this_thread::sleep_for(1s);  // both stream at 1 kHz all the while

  EXPECT_EQ(device_status().commands.received, 0U) << "a command from outside the deployment reached robotd";
  const JointState after = joint_state();
  for (std::size_t j = 0; j < after.position.size(); ++j) EXPECT_NEAR(after.position[j], before.position[j], 1e-3);

  // robotd was listening all along: the operator's own command moves the arm.
  ASSERT_TRUE(session.value().send_positions({0.3F, 0, 0, 0, 0, 0}));
  EXPECT_TRUE(wait_for_joints([](const JointState& s) { return std::fabs(s.position[0] - 0.3) < 0.01; }, 5s));
}

}  // namespace
}  // namespace robotd::testing
