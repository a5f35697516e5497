// robotd-piper-sim: an AgileX PiPER main controller on the CAN wire protocol, for tests and the
// no-hardware demo. README.md in this folder describes the options and the control channel.
//
//   robotd-piper-sim --standin /tmp/piper.sock --control /tmp/piper.ctl
//
// Prints "ready" once the bus and the control socket listen; runs until SIGTERM or SIGINT.
#include <csignal>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "firmware_info.hpp"
#include "robotd/sim_control/sim_main.hpp"
#include "simulator.hpp"

namespace {

constexpr const char* kProgram = "robotd-piper-sim";

int fail(const std::string& message) { return robotd::sim_control::usage_error(kProgram, message); }

}  // namespace

int main(int argc, char** argv) {
  using robotd::piper::sim::SimOptions;
  CLI::App app{"robotd-piper-sim: an AgileX PiPER arm (main controller, six joints, gripper) on the CAN wire protocol"};
  SimOptions options;
  std::string standin_path;
  std::string interface;
  std::string dh = "offset";
  std::string initial;
  auto* standin_option =
      app.add_option("--standin", standin_path, "listen as the stand-in CAN bus at this unix seqpacket socket path");
  auto* interface_option = app.add_option("--interface", interface, "join this SocketCAN interface (can0, vcan0)");
  standin_option->excludes(interface_option);
  app.add_option("--control", options.control_path, "the control channel's unix stream socket path (tests)");
  app.add_option("--firmware", options.firmware, "the software version the arm reports on 0x4AF")
      ->capture_default_str();
  app.add_option("--dh", dh, "the DH table of the reported end pose: offset (firmware ≥ S-V1.6-3) or plain")
      ->check(CLI::IsMember({"offset", "plain"}))
      ->capture_default_str();
  app.add_option("--feedback-rate-hz", options.feedback_rate_hz,
                 "rate of the 0x2A1–0x2A8 and 0x251–0x256 feedback; 0x261–0x266 run at a fifth of it")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  app.add_option("--initial", initial, "the joints at start, rad: q1,q2,q3,q4,q5,q6 (default all 0)");
  std::string role = "follower";
  app.add_option("--role", role,
                 "follower: stream feedback and take commands; leader: send a leader arm's commands (0x151, "
                 "0x155-0x157, 0x159) from the joints, no feedback")
      ->check(CLI::IsMember({"follower", "leader"}))
      ->capture_default_str();
  int feedback_offset = 0;
  int control_offset = 0;
  app.add_option("--feedback-id-offset", feedback_offset,
                 "MasterSlaveConfig feedback offset: 0x2A1-0x2A8 go out at 0x2B1-0x2B8 (16) or 0x2C1-0x2C8 (32)")
      ->check(CLI::IsMember({0, 16, 32}))
      ->capture_default_str();
  app.add_option("--control-id-offset", control_offset,
                 "MasterSlaveConfig control offset (a leader's linkage offset): 0x150-0x15F are taken (a leader "
                 "sends them) at 0x160-0x16F (16) or 0x170-0x17F (32)")
      ->check(CLI::IsMember({0, 16, 32}))
      ->capture_default_str();
  app.add_flag("--quiet", options.quiet, "log only warnings and errors to stderr");
  int rt_priority = 0;
  robotd::sim_control::add_rt_priority_option(app, rt_priority);
  if (const auto exit_status = robotd::sim_control::parse_command_line(app, argc, argv)) return *exit_status;

  if (standin_option->count() == 0 && interface_option->count() == 0) {
    return fail("say where the bus is: --standin PATH (unix socket stand-in) or --interface NAME (SocketCAN)");
  }
  if (standin_option->count() != 0) {
    options.bus.kind = robotd::transport::CanLinkConfig::Kind::kStandIn;
    options.bus.path = standin_path;
  } else {
    options.bus.kind = robotd::transport::CanLinkConfig::Kind::kSocketCan;
    options.bus.interface = interface;
  }
  options.dh = dh == "plain" ? robotd::piper::DhVariant::kPlain : robotd::piper::DhVariant::kOffset;
  options.leader = role == "leader";
  options.feedback_id_offset = static_cast<std::uint8_t>(feedback_offset);
  options.control_id_offset = static_cast<std::uint8_t>(control_offset);
  if (robotd::piper::software_version(robotd::piper::sim::firmware_text(options.firmware)) != options.firmware) {
    return fail("--firmware '" + options.firmware +
                "' is not a version the arm could report: 8 characters such as S-V1.8-2");
  }
  if (!initial.empty()) {
    auto joints = robotd::piper::sim::parse_initial_joints(initial);
    if (!joints) return fail(joints.error().message);
    options.initial_rad = joints.value();
  }

  robotd::sim_control::log_to_stderr(kProgram, options.quiet);
  robotd::sim_control::run_at_rt_priority(rt_priority);

  robotd::piper::sim::Simulator simulator(options);
  if (auto opened = simulator.open(); !opened) return fail(opened.error().message);

  const volatile std::sig_atomic_t& stop_requested = robotd::sim_control::stop_on_signals();

  spdlog::info("{} firmware {}, {} {} Hz, id offsets feedback 0x{:02X} control 0x{:02X}{}",
               options.bus.kind == robotd::transport::CanLinkConfig::Kind::kStandIn
                   ? "stand-in bus " + options.bus.path
                   : "SocketCAN " + options.bus.interface,
               options.firmware, options.leader ? "leader commands" : "feedback", options.feedback_rate_hz,
               options.feedback_id_offset, options.control_id_offset,
               options.control_path.empty() ? "" : ", control " + options.control_path);
  robotd::sim_control::announce_ready();
  simulator.run(stop_requested);
  return 0;
}
