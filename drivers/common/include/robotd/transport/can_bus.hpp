// The simulator's side of a CAN link: where a simulated device sits on the bus. It has the
// CanTransport interface, so a simulator is written once and runs on either link:
//   stand-in:  listens on a unix seqpacket socket; every connected peer (robotd's driver, a bus
//              monitor) is a node: a frame from one node reaches all others and the simulator,
//              and the simulator's frames reach every node, as on a real bus.
//   socketcan: a raw socket on a (v)CAN interface, like any other node.
#pragma once

#include <memory>

#include "robotd/transport/can_transport.hpp"

namespace robotd::transport {

std::unique_ptr<CanTransport> make_can_bus(const CanLinkConfig& config);

}  // namespace robotd::transport
