// Where robotd's DDS traffic goes. The default keeps every packet on loopback: interface
// 127.0.0.1, no multicast, unicast discovery to 127.0.0.1. A robot on a network names its
// interface (address or name) and either enables multicast or lists its peers. With DDS
// Security files the participant authenticates, is access-controlled and encrypts its traffic.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "robotd/dds_security.hpp"

namespace robotd::wire {

struct DdsSettings {
  int domain_id = 0;
  std::string network_interface = "127.0.0.1";  // address or interface name; "" = Cyclone picks
  bool multicast = false;
  std::vector<std::string> peers{"127.0.0.1"};  // unicast discovery peers (needed without multicast)
  int max_participant_index = 120;              // participants per host reachable by unicast discovery
  // > 0: one receive thread for every socket, at SCHED_FIFO this priority, so that busy processes
  // on the host cannot keep it from draining its sockets (robotd: docs/reliability.md, "Command
  // flood"). 0: Cyclone's default threads and scheduling.
  int receive_thread_priority = 0;
  // > 0: the stack size of each of Cyclone's threads (Threads/Thread/StackSize); robotd sets it so
  // that no Cyclone thread reserves the process default (8 MiB). 0: the system default.
  std::size_t thread_stack_bytes = 0;
  std::string cyclonedds_xml;  // non-empty: used verbatim instead of the fields above
  DdsSecurityFiles security;   // any file named: DDS Security on, as the domain's <Security>
};

/// The Cyclone DDS configuration (XML) for `settings`. Cyclone applies it, DDS Security
/// included, to the whole domain in this process: every participant of a process on one
/// domain shares one identity.
std::string to_cyclone_xml(const DdsSettings& settings);

/// Defaults overridden by ROBOTD_DOMAIN_ID, ROBOTD_DDS_INTERFACE, ROBOTD_DDS_PEERS
/// (comma-separated), ROBOTD_DDS_MULTICAST=1 and the DDS Security files
/// ROBOTD_DDS_SECURITY_<FIELD> (IDENTITY_CA, IDENTITY_CERTIFICATE, PRIVATE_KEY, PERMISSIONS_CA,
/// GOVERNANCE, PERMISSIONS), so tools follow the daemon's deployment.
DdsSettings dds_settings_from_environment();

}  // namespace robotd::wire
