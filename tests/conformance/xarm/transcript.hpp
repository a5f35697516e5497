// transcript.json as the tests use it: the command connection's exchanges (a request and the
// reply with its transaction id), the motion-feedback frames the controller sent unasked, and the
// first packets of each report connection.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec/xarm_codec.hpp"

namespace robotd::conformance::xarm {

struct Exchange {
  std::string step;  // the session step that sent it ("enable", "gripper" …)
  robotd::xarm::Bytes request;
  robotd::xarm::Bytes reply;  // the whole frame
  robotd::xarm::Frame request_frame;
  robotd::xarm::Frame reply_frame;
  /// What the session asked the simulator's control channel before this request (a fault).
  std::vector<nlohmann::json> control_before;
};

struct ReportConnection {
  robotd::xarm::ReportKind kind = robotd::xarm::ReportKind::kRich;
  std::vector<robotd::xarm::Bytes> packets;
};

struct Transcript {
  std::vector<Exchange> exchanges;
  std::vector<robotd::xarm::Bytes> feedback;  // whole motion-feedback frames (register 0xFF)
  std::vector<ReportConnection> reports;
  std::string model;
  std::string firmware;
};

/// transcript.json of this vendor's data directory; throws std::runtime_error saying what is wrong
/// (a reply without its request, a frame that does not parse …).
const Transcript& transcript();

}  // namespace robotd::conformance::xarm
