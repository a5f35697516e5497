// What the command line sets (main.cpp): the ports, the arm model and firmware it claims, the
// control channel.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace robotd::xarm::sim {

struct SimOptions {
  std::string host = "127.0.0.1";
  std::uint16_t port = 0;                             // --port: the command port (required; the arm's 502)
  std::optional<std::uint16_t> report_port;           // --report-port: "real" report, 100 Hz (the arm's 30003)
  std::optional<std::uint16_t> normal_report_port;    // --normal-report-port: 5 Hz (30001)
  std::optional<std::uint16_t> realtime_report_port;  // --realtime-report-port: 250 Hz (30000)
  std::optional<std::uint16_t> rich_report_port;      // --rich-report-port: 5 Hz (30002, the SDK's default)
  bool report_force_torque = false;                   // --report-ft: 135-byte real reports
  std::string model = "xarm6";
  std::string firmware = "2.3.0";
  std::string control_path;  // --control; empty: no control channel
  bool quiet = false;
};

}  // namespace robotd::xarm::sim
