#include "client_options.hpp"

#include <string>
#include <string_view>
#include <vector>

#include "arguments.hpp"
#include "errors.hpp"

namespace robotd::c {
namespace {

std::vector<std::string> split_peers(std::string_view list) {
  std::vector<std::string> peers;
  while (!list.empty()) {
    const std::size_t comma = list.find(',');
    std::string_view peer = list.substr(0, comma);
    const std::size_t first = peer.find_first_not_of(" \t");
    peer = first == std::string_view::npos ? std::string_view{}
                                           : peer.substr(first, peer.find_last_not_of(" \t") + 1 - first);
    if (!peer.empty()) peers.emplace_back(peer);
    list = comma == std::string_view::npos ? std::string_view{} : list.substr(comma + 1);
  }
  return peers;
}

std::string join_peers(const std::vector<std::string>& peers) {
  std::string list;
  for (const auto& peer : peers) list += (list.empty() ? "" : ",") + peer;
  return list;
}

}  // namespace

ClientOptions to_client_options(const robotd_client_options& options) {
  ClientOptions converted = ClientOptions::from_environment();
  converted.domain_id = options.domain_id;
  converted.network_interface = optional_text(options.network_interface);
  converted.peers = split_peers(optional_text(options.peers));
  converted.multicast = options.multicast;
  converted.node_name = optional_text(options.node_name);
  converted.service_timeout = timeout_argument(options.service_timeout_ms, "options->service_timeout_ms", false);
  return converted;
}

}  // namespace robotd::c

using robotd::c::guarded;
using robotd::c::join_peers;
using robotd::c::require;

extern "C" robotd_status robotd_client_options_init(robotd_client_options* options) {
  return guarded("robotd_client_options_init", [&] {
    auto& out = require(options, "options", "a robotd_client_options to fill");
    // The strings the struct points at: the calling thread's, until its next call here.
    thread_local robotd::ClientOptions defaults;
    thread_local std::string peers;
    defaults = robotd::ClientOptions::from_environment();
    peers = join_peers(defaults.peers);
    out.domain_id = defaults.domain_id;
    out.network_interface = defaults.network_interface.c_str();
    out.peers = peers.c_str();
    out.multicast = defaults.multicast;
    out.node_name = defaults.node_name.c_str();
    out.service_timeout_ms = static_cast<std::int32_t>(defaults.service_timeout.count());
  });
}
