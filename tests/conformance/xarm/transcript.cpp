#include "transcript.hpp"

#include <stdexcept>

#include "vector_file.hpp"

namespace robotd::conformance::xarm {
namespace {

using robotd::xarm::Bytes;
using robotd::xarm::Frame;

Frame single_frame(const Bytes& bytes) {
  robotd::xarm::FrameSplitter splitter;
  splitter.append(bytes);
  auto frame = splitter.next();
  if (!frame || !frame.value() || splitter.buffered() != 0) {
    throw std::runtime_error("transcript.json: " + hex_text(bytes) + " is not one command-port frame");
  }
  return *frame.value();
}

/// The connection's exchanges; its motion-feedback frames go to `feedback`.
std::vector<Exchange> exchanges_of(const nlohmann::json& frames, std::vector<Bytes>& feedback) {
  std::vector<Exchange> exchanges;
  for (const auto& frame : frames) {
    const Bytes bytes = hex_bytes(frame.at("hex").get<std::string>());
    if (frame.at("dir") == "request") {
      exchanges.push_back(Exchange{.step = frame.at("step").get<std::string>(),
                                   .request = bytes,
                                   .reply = {},
                                   .request_frame = single_frame(bytes),
                                   .reply_frame = {},
                                   .control_before = {}});
      continue;
    }
    const Frame reply = single_frame(bytes);
    if (robotd::xarm::is_motion_feedback(reply)) {
      feedback.push_back(bytes);
      continue;
    }
    if (exchanges.empty() || !exchanges.back().reply.empty() ||
        exchanges.back().request_frame.transaction_id != reply.transaction_id) {
      throw std::runtime_error("transcript.json: reply " + hex_text(bytes) + " follows no request of its id");
    }
    exchanges.back().reply = bytes;
    exchanges.back().reply_frame = reply;
  }
  return exchanges;
}

Transcript load() {
  const nlohmann::json data = load_json("transcript.json");
  Transcript loaded;
  loaded.model = data.at("simulator").at("model").get<std::string>();
  loaded.firmware = data.at("simulator").at("firmware").get<std::string>();
  for (const auto& connection : data.at("connections")) {
    const std::string kind = connection.at("kind").get<std::string>();
    if (kind == "command") {
      auto exchanges = exchanges_of(connection.at("frames"), loaded.feedback);
      loaded.exchanges.insert(loaded.exchanges.end(), exchanges.begin(), exchanges.end());
      continue;
    }
    const auto report_kind = robotd::xarm::parse_report_kind(kind);
    if (!report_kind) throw std::runtime_error("transcript.json: unknown connection kind \"" + kind + "\"");
    ReportConnection report{.kind = *report_kind, .packets = {}};
    for (const auto& frame : connection.at("frames"))
      report.packets.push_back(hex_bytes(frame.at("hex").get<std::string>()));
    loaded.reports.push_back(std::move(report));
  }
  if (loaded.exchanges.empty()) throw std::runtime_error("transcript.json has no command exchanges");
  for (const auto& control : data.at("simulator_control")) {
    const auto before = control.at("before_request").get<std::size_t>();
    if (before >= loaded.exchanges.size()) {
      throw std::runtime_error("transcript.json: a simulator_control entry comes after the last request");
    }
    loaded.exchanges[before].control_before.push_back(control.at("request"));
  }
  return loaded;
}

}  // namespace

const Transcript& transcript() {
  static const Transcript loaded = load();
  return loaded;
}

}  // namespace robotd::conformance::xarm
