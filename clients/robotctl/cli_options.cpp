#include "cli_options.hpp"

#include <charconv>
#include <chrono>
#include <optional>
#include <string_view>

#include "text_format.hpp"

namespace robotctl {
namespace {

// Far above any robot's joint count; keeps a typo such as 0-100000 from expanding into a huge list.
constexpr std::int32_t kLargestMotorId = 1023;

std::optional<std::int32_t> parse_motor_id(std::string_view text) {
  std::int32_t id = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), id);
  if (error != std::errc() || end != text.data() + text.size() || id < 0 || id > kLargestMotorId) {
    return std::nullopt;
  }
  return id;
}

// "0,1,4-6" -> {0, 1, 4, 5, 6}; nullopt unless every part is an id (0..kLargestMotorId) or an
// ascending range of them.
std::optional<std::vector<std::int32_t>> parse_motor_ids(std::string_view text) {
  std::vector<std::int32_t> ids;
  while (true) {
    const std::size_t comma = text.find(',');
    const std::string_view part = text.substr(0, comma);
    const std::size_t dash = part.find('-');
    const auto first = parse_motor_id(part.substr(0, dash));
    const auto last = dash == std::string_view::npos ? first : parse_motor_id(part.substr(dash + 1));
    if (!first || !last || *last < *first) return std::nullopt;
    for (std::int32_t id = *first; id <= *last; ++id) ids.push_back(id);
    if (comma == std::string_view::npos) return ids;
    text.remove_prefix(comma + 1);
  }
}

}  // namespace

void add_connection_options(CLI::App& app, robotd::ClientOptions& options) {
  const std::string connection =
      "Connection (defaults from ROBOTD_DOMAIN_ID, ROBOTD_DDS_INTERFACE, ROBOTD_DDS_PEERS, "
      "ROBOTD_DDS_MULTICAST; the DDS Security identity from ROBOTD_DDS_SECURITY_*, see docs/security.md)";
  app.add_option("--domain", options.domain_id, "DDS domain id robotd runs on")
      ->check(CLI::Range(0, 232))
      ->capture_default_str()
      ->group(connection);
  app.add_option("--interface", options.network_interface,
                 "Network interface for DDS: an address (127.0.0.1) or a name (eth0)")
      ->capture_default_str()
      ->group(connection);
  app.add_option("--peers", options.peers, "Hosts to discover robotd on by unicast, comma-separated")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->default_str(join(options.peers, ","))
      ->group(connection);
  app.add_flag("--multicast", options.multicast, "Discover robotd by multicast")->group(connection);
  app.add_option_function<int>(
         "--timeout-ms",
         [&options](int timeout_ms) { options.service_timeout = std::chrono::milliseconds(timeout_ms); },
         "Longest wait for each answer from robotd, in ms (after acquire, --timeout-ms is the session timeout; put "
         "this one before the verb)")
      ->check(CLI::Range(1, 600'000))
      ->default_str(std::to_string(options.service_timeout.count()))
      ->group(connection);
  app.add_option("--node-name", options.node_name, "Name robotd shows for this client (sessions, e-stop log)")
      ->capture_default_str()
      ->group(connection);
}

CLI::Option* add_motors_option(CLI::App& command, std::vector<std::int32_t>& motor_ids) {
  const CLI::Validator id_list(
      [](const std::string& text) {
        return parse_motor_ids(text) ? std::string() : "expected motor ids such as 0,1,2 or 0-3,5, got '" + text + "'";
      },
      "IDS");
  return command
      .add_option_function<std::string>(
          "--motors", [&motor_ids](const std::string& text) { motor_ids = parse_motor_ids(text).value(); },
          "Motor ids, comma-separated, with ranges (default: every motor of the device)")
      ->check(id_list);
}

CLI::Option* add_control_mode_option(CLI::App& command, robotd::ControlMode& mode) {
  return command
      .add_option_function<std::string>(
          "--mode", [&mode](const std::string& text) { mode = robotd::parse_control_mode(text).value(); },
          "How the session commands its motors")
      ->check(CLI::IsMember({"position", "torque", "mixed"}, CLI::ignore_case))
      ->default_str(lowercase(robotd::to_string(mode)));
}

CLI::Option* add_behavior_option(CLI::App& command, const std::string& name, robotd::Behavior& behavior,
                                 const std::string& description) {
  return command
      .add_option_function<std::string>(
          name, [&behavior](const std::string& text) { behavior = robotd::parse_behavior(text).value(); }, description)
      ->check(CLI::IsMember({"keep", "damping", "zero_torque"}, CLI::ignore_case))
      ->default_str(lowercase(robotd::to_string(behavior)));
}

}  // namespace robotctl
