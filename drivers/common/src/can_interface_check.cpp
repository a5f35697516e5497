#include "robotd/transport/can_interface_check.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string_view>

namespace robotd::transport {
namespace {

constexpr int kArphrdCan = 280;  // ARPHRD_CAN: the type of every CAN and vcan interface

std::string read_line(const std::string& path) {
  std::ifstream file(path);
  std::string line;
  std::getline(file, line);
  return line;
}

/// What `ip -details link show <name>` says, or "" if ip cannot be run.
std::string ip_details(const std::string& name) {
  const std::string command = "ip -details link show " + name + " 2>/dev/null";
  // A fixed command; name is an interface name.
  FILE* pipe = popen(command.c_str(), "r");  // NOLINT(cert-env33-c,bugprone-command-processor)
  if (pipe == nullptr) return {};
  std::string output;
  char buffer[512];
  while (std::fgets(buffer, sizeof(buffer), pipe) != nullptr) output += buffer;
  pclose(pipe);
  return output;
}

std::string setup_hint(const std::string& name, std::uint32_t bitrate) {
  return "sudo ip link set " + name + " up type can bitrate " + std::to_string(bitrate == 0 ? 1000000 : bitrate);
}

bool is_interface_name(const std::string& name) {
  if (name.empty() || name.size() > 15) return false;
  for (const char c : name) {
    const bool ok =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
    if (!ok) return false;
  }
  return true;
}

}  // namespace

Result<void> check_can_interface(const std::string& name, std::uint32_t bitrate) {
  if (!is_interface_name(name)) {
    return make_error(ErrorCode::kInvalidArgument,
                      "'" + name + "' is not an interface name (expected up to 15 letters, digits, _ - .)");
  }
  const std::string sys = "/sys/class/net/" + name;
  const std::string type = read_line(sys + "/type");
  if (type.empty()) {
    return make_error(ErrorCode::kNotAvailable, "CAN interface " + name +
                                                    " does not exist: is the USB-CAN adapter plugged in? (ip link "
                                                    "lists the interfaces)");
  }
  if (type != std::to_string(kArphrdCan)) {
    return make_error(ErrorCode::kInvalidArgument, name + " is not a CAN interface (link type " + type + ")");
  }
  const std::string state = read_line(sys + "/operstate");
  const std::string details = ip_details(name);
  const bool is_virtual = details.find("vcan") != std::string::npos;
  if (state != "up" && !(is_virtual && state == "unknown")) {
    return make_error(ErrorCode::kNotAvailable,
                      "CAN interface " + name + " is not up (state " + state + "): " + setup_hint(name, bitrate));
  }
  if (bitrate == 0 || is_virtual || details.empty()) return {};
  const std::size_t at = details.find("bitrate ");
  if (at == std::string::npos) {
    return make_error(ErrorCode::kNotAvailable,
                      "CAN interface " + name + " reports no bitrate: " + setup_hint(name, bitrate));
  }
  std::istringstream in(details.substr(at + std::string_view("bitrate ").size()));
  std::uint64_t actual = 0;
  in >> actual;
  if (actual != bitrate) {
    return make_error(ErrorCode::kInvalidArgument, "CAN interface " + name + " runs at " + std::to_string(actual) +
                                                       " bit/s, the device needs " + std::to_string(bitrate) +
                                                       ": sudo ip link set " + name + " down; " +
                                                       setup_hint(name, bitrate));
  }
  return {};
}

}  // namespace robotd::transport
