// How a client reaches robotd over DDS. The defaults match robotd's default config (domain 0,
// loopback only); from_environment() lets tools follow a deployment without flags.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "robotd/dds_security.hpp"

namespace robotd {

struct ClientOptions {
  int domain_id = 0;
  std::string network_interface = "127.0.0.1";  // address or name; "" = Cyclone picks
  bool multicast = false;
  std::vector<std::string> peers{"127.0.0.1"};
  std::string cyclonedds_xml;  // non-empty: used verbatim instead of the fields above
  DdsSecurityFiles security;   // this client's DDS Security identity; none named = DDS Security off
  std::string node_name = "robotd_client";
  std::chrono::milliseconds service_timeout{2000};  // longest any service call waits

  /// Defaults overridden by ROBOTD_DOMAIN_ID, ROBOTD_DDS_INTERFACE, ROBOTD_DDS_PEERS
  /// (comma-separated), ROBOTD_DDS_MULTICAST=1 and ROBOTD_DDS_SECURITY_<FIELD> for each
  /// DdsSecurityFiles field (e.g. ROBOTD_DDS_SECURITY_IDENTITY_CERTIFICATE; scripts/make-dds-security
  /// writes them into each participant's dds-security.env).
  static ClientOptions from_environment();
};

}  // namespace robotd
