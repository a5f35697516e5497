#include "robotd/transport/can_transport.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <linux/can/error.h>
#include <string>

#include "socketcan_transport.hpp"
#include "standin_can_transport.hpp"

namespace robotd::transport {

CanLinkConfig read_can_link(JsonReader& reader) {
  CanLinkConfig config;
  const std::string kind = reader.string_or("transport", "socketcan", {"socketcan", "standin"});
  config.fd = reader.boolean_or("fd", false);
  if (kind == "standin") {
    config.kind = CanLinkConfig::Kind::kStandIn;
    reader.require("path", "the unix socket path the simulator listens on");
    config.path = reader.string_or("path", "");
  } else {
    config.kind = CanLinkConfig::Kind::kSocketCan;
    config.interface = reader.string_or("interface", config.interface);
  }
  reader.finish();
  return config;
}

std::unique_ptr<CanTransport> make_can_transport(const CanLinkConfig& config) {
  if (config.kind == CanLinkConfig::Kind::kStandIn) return std::make_unique<StandInCanTransport>(config.path);
  return std::make_unique<SocketCanTransport>(config.interface, config.fd);
}

void describe_bus_error(const CanMessage& error_frame, std::span<char> out) noexcept {
  if (out.empty()) return;
  std::size_t used = 0;
  out[0] = '\0';
  const auto add = [&](const char* what) {
    const int written = std::snprintf(out.data() + used, out.size() - used, "%s%s", used == 0 ? "" : ", ", what);
    if (written > 0) used = std::min(out.size() - 1, used + static_cast<std::size_t>(written));
  };
  const std::uint32_t classes = error_frame.id;
  if ((classes & CAN_ERR_BUSOFF) != 0) add("bus off");
  if ((classes & CAN_ERR_RESTARTED) != 0) add("controller restarted");
  if ((classes & CAN_ERR_TX_TIMEOUT) != 0) add("transmit timeout");
  if ((classes & CAN_ERR_LOSTARB) != 0) add("arbitration lost");
  if ((classes & CAN_ERR_ACK) != 0) add("no acknowledgement (no other node on the bus? wrong bitrate?)");
  if ((classes & CAN_ERR_BUSERROR) != 0) add("bus error");
  if ((classes & CAN_ERR_PROT) != 0) add("protocol violation");
  if ((classes & CAN_ERR_TRX) != 0) add("transceiver problem (cable?)");
  if ((classes & CAN_ERR_CRTL) != 0) {
    const std::uint8_t state = error_frame.length > 1 ? error_frame.data[1] : 0;
    if ((state & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0) {
      add("controller error-passive");
    } else if ((state & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) != 0) {
      add("controller error warning");
    } else if ((state & (CAN_ERR_CRTL_RX_OVERFLOW | CAN_ERR_CRTL_TX_OVERFLOW)) != 0) {
      add("controller buffer overflow");
    } else {
      add("controller problem");
    }
  }
  if (used == 0) add("unknown CAN error");
}

std::string describe_bus_error(const CanMessage& error_frame) {
  std::array<char, 256> text{};
  describe_bus_error(error_frame, text);
  return text.data();
}

}  // namespace robotd::transport
