// robotd-hightorque-sim: HighTorque motors on CAN-FD buses (the stand-in or SocketCAN) and on
// ports of the livelybot USB-CDC CAN board (ptys), for tests and the no-hardware demo. README.md
// in this folder describes the options and the control channel.
//
//   robotd-hightorque-sim --bus /tmp/legs.sock:1-12 --board /tmp/arms.tty:13-23 --control /tmp/ht.ctl
//
// Prints "ready" once every bus and the control socket listen; runs until SIGTERM or SIGINT.
#include <csignal>
#include <map>
#include <set>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "robotd/sim_control/sim_main.hpp"
#include "simulator.hpp"

namespace {

constexpr const char* kProgram = "robotd-hightorque-sim";

int fail(const std::string& message) { return robotd::sim_control::usage_error(kProgram, message); }

}  // namespace

int main(int argc, char** argv) {
  using robotd::hightorque::sim::BusSpec;
  using robotd::hightorque::sim::SimOptions;
  namespace sim = robotd::hightorque::sim;
  CLI::App app{"robotd-hightorque-sim: HighTorque motors on CAN-FD buses and livelybot USB-CDC board ports"};
  SimOptions options;
  std::vector<std::string> bus_specs;
  std::vector<std::string> interface_specs;
  std::vector<std::string> board_specs;
  std::string firmware = "0.3.3";
  auto* bus_option = app.add_option("--bus", bus_specs,
                                    "PATH:IDS, a CAN-FD bus on the stand-in socket PATH with motors IDS (1-6, "
                                    "1,2,5, 1-4,7); repeatable");
  auto* interface_option =
      app.add_option("--interface", interface_specs, "NAME:IDS, the same on a SocketCAN interface; repeatable");
  auto* board_option = app.add_option("--board", board_specs,
                                      "PATH:IDS, a USB-CDC CAN board port on a pty (symlink at PATH) with motors "
                                      "IDS; repeatable");
  app.add_option("--control", options.control_path, "the control channel's unix stream socket path (tests)");
  app.add_option("--inertia", options.physics.inertia_kg_m2, "each rotor's inertia, kg·m²")
      ->check(CLI::Range(1e-5, 100.0))
      ->capture_default_str();
  app.add_option("--friction", options.physics.friction_nm_s_rad, "viscous friction, N·m·s/rad")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  app.add_option("--torque-max", options.physics.torque_max_nm, "every motor's torque saturates here, N·m")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  app.add_option("--model", options.model, "the model name 00 07 answers (also picks the board's torque unit)")
      ->capture_default_str();
  app.add_option("--firmware", firmware, "the firmware version 00 04 answers, MAJOR.MINOR.PATCH")
      ->capture_default_str();
  app.add_option("--gain-factor", options.gain_factor,
                 "MotorScaling gain_factor: wire gain = N·m/rad × 2π / factor (must match the driver's config)")
      ->check(CLI::Range(1e-6, 1e6))
      ->capture_default_str();
  app.add_option("--board-torque-unit", options.board_torque_per_unit,
                 "N·m per board torque unit (default: the model's SDK factor, 0.01 for unknown models)")
      ->check(CLI::Range(1e-6, 10.0));
  std::string board_firmware = "4.3";
  app.add_option("--board-firmware", board_firmware,
                 "the boards' own firmware, MAJOR.MINOR (0x05 answer; 4.1 and later take the FDCAN reset 0x0E)")
      ->capture_default_str();
  std::vector<std::string> board_motor_firmware;
  app.add_option("--board-motor-firmware", board_motor_firmware,
                 "[IDS:]MAJOR.MINOR.PATCH, the firmware the board reports (0x0B) for motors IDS (all without "
                 "IDS; default 4.4.6); repeatable, later ones win");
  app.add_flag("--quiet", options.quiet, "log only warnings and errors to stderr");
  int rt_priority = 0;
  robotd::sim_control::add_rt_priority_option(app, rt_priority);
  if (const auto exit_status = robotd::sim_control::parse_command_line(app, argc, argv)) return *exit_status;

  // The buses in command-line order: that is the control channel's "bus" index.
  std::map<const CLI::Option*, std::size_t> taken;
  for (const CLI::Option* option : app.parse_order()) {
    BusSpec::Kind kind = BusSpec::Kind::kStandIn;
    const std::vector<std::string>* values = &bus_specs;
    if (option == interface_option) {
      kind = BusSpec::Kind::kSocketCan;
      values = &interface_specs;
    } else if (option == board_option) {
      kind = BusSpec::Kind::kBoard;
      values = &board_specs;
    } else if (option != bus_option) {
      continue;
    }
    std::size_t& index = taken[option];
    if (index >= values->size()) continue;
    auto spec = sim::parse_bus_spec(kind, values->at(index++), option->get_name());
    if (!spec) return fail(spec.error().message);
    options.buses.push_back(std::move(spec.value()));
  }
  if (options.buses.empty()) {
    return fail(
        "say where the motors are: --bus PATH:IDS (stand-in CAN-FD), --interface NAME:IDS (SocketCAN) or "
        "--board PATH:IDS (USB-CDC board port on a pty), each repeatable");
  }
  std::set<std::string> paths;
  for (const BusSpec& spec : options.buses) {
    if (!paths.insert(spec.path).second) return fail(spec.path + " is given for two buses: one bus per path");
  }
  auto version = sim::parse_firmware(firmware);
  if (!version) return fail(version.error().message);
  options.firmware = version.value();
  auto board_version = sim::parse_board_firmware(board_firmware);
  if (!board_version) return fail(board_version.error().message);
  options.board_firmware = board_version.value();
  for (const std::string& text : board_motor_firmware) {
    auto motor_firmware = sim::parse_board_motor_firmware(text);
    if (!motor_firmware) return fail(motor_firmware.error().message);
    options.board_motor_firmware.push_back(std::move(motor_firmware.value()));
  }
  if (options.model.empty() || options.model.size() > 59) return fail("--model needs a name of 1 … 59 characters");

  robotd::sim_control::log_to_stderr(kProgram, options.quiet);
  robotd::sim_control::run_at_rt_priority(rt_priority);

  sim::Simulator simulator(options);
  if (auto opened = simulator.open(); !opened) return fail(opened.error().message);

  const volatile std::sig_atomic_t& stop_requested = robotd::sim_control::stop_on_signals();

  for (const BusSpec& spec : options.buses) {
    std::string ids;
    for (const int id : spec.ids) ids += (ids.empty() ? "" : ",") + std::to_string(id);
    spdlog::info("{} {}: motors {}",
                 spec.kind == BusSpec::Kind::kBoard       ? "board port"
                 : spec.kind == BusSpec::Kind::kSocketCan ? "SocketCAN"
                                                          : "stand-in bus",
                 spec.path, ids);
  }
  spdlog::info("model {}, firmware {}, J {} kg·m², friction {} N·m·s/rad, torque max {} N·m{}", options.model, firmware,
               options.physics.inertia_kg_m2, options.physics.friction_nm_s_rad, options.physics.torque_max_nm,
               options.control_path.empty() ? "" : ", control " + options.control_path);
  robotd::sim_control::announce_ready();
  simulator.run(stop_requested);
  return 0;
}
