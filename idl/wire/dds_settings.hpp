// Where robotd's DDS traffic goes. The default keeps every packet on loopback: interface
// 127.0.0.1, no multicast, unicast discovery to 127.0.0.1. A robot on a network names its
// interface (address or name) and either enables multicast or lists its peers.
#pragma once

#include <string>
#include <vector>

namespace robotd::wire {

struct DdsSettings {
  int domain_id = 0;
  std::string network_interface = "127.0.0.1";  // address or interface name; "" = Cyclone picks
  bool multicast = false;
  std::vector<std::string> peers{"127.0.0.1"};  // unicast discovery peers (needed without multicast)
  int max_participant_index = 120;              // participants per host reachable by unicast discovery
  std::string cyclonedds_xml;                   // non-empty: used verbatim instead of the fields above
};

/// The Cyclone DDS configuration (XML) for `settings`.
std::string to_cyclone_xml(const DdsSettings& settings);

/// Defaults overridden by ROBOTD_DOMAIN_ID, ROBOTD_DDS_INTERFACE, ROBOTD_DDS_PEERS
/// (comma-separated) and ROBOTD_DDS_MULTICAST=1, so tools follow the daemon's deployment.
DdsSettings dds_settings_from_environment();

}  // namespace robotd::wire
