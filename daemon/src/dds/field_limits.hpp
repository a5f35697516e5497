// Every string and list a client sends, held to its limit (robotd/limits.hpp) before robotd
// acts on it. One check per message type, so the table in docs/dds-interface.md ("Limits")
// has one place to match.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "robotd/messages.hpp"

namespace robotd::dds {

/// The first field of a message beyond its limit.
struct Oversize {
  const char* field = "";
  std::size_t length = 0;  // bytes of a string, entries of a list
  std::size_t limit = 0;
  bool is_list = false;

  /// "node_name is 1048576 bytes long; the limit is 255 bytes".
  std::string describe() const;
};

std::optional<Oversize> find_oversize(const ControlCommand& command);
std::optional<Oversize> find_oversize(const RequestControlRequest& request);
std::optional<Oversize> find_oversize(const ReleaseControlRequest& request);
std::optional<Oversize> find_oversize(const GetAvailableMotorsRequest& request);
std::optional<Oversize> find_oversize(const ResetZeroRequest& request);
/// Only `device`: an e-stop is never refused for its words (cut_to_limits).
std::optional<Oversize> find_oversize(const EstopRequest& request);
std::optional<Oversize> find_oversize(const ListDevicesRequest& request);
std::optional<Oversize> find_oversize(const DeviceCallRequest& request);

/// Cuts an e-stop's node_name and reason to their limits (at a UTF-8 character boundary), so
/// that the e-stop engages whatever they say. Returns the first field it cut, if any.
std::optional<Oversize> cut_to_limits(EstopRequest& request);

}  // namespace robotd::dds
