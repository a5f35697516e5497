// For drivers whose controller takes joint position targets (a stream of setpoints): the targets
// of one tick from robotd's command frame. RT-safe: no allocation.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

#include "robotd/driver/types.hpp"

namespace robotd::driver {

/// Writes each of the first `dof` joints' target into `targets`: its commanded position when the
/// loop positions it, else `measured` (a joint nobody drives stays where it is). True when a
/// session owns a positioned joint, i.e. there is something to stream.
template <std::size_t N>
bool position_targets(const CommandFrame& command, std::size_t dof, const std::array<double, N>& measured,
                      std::array<double, N>& targets) noexcept {
  bool owned = false;
  const std::size_t commanded = std::min(command.joint_count, dof);
  for (std::size_t j = 0; j < dof && j < N; ++j) {
    const bool positioned = j < commanded && command.joints[j].kind == JointCommandKind::kPosition;
    targets[j] = positioned ? command.joints[j].position_rad : measured[j];
    owned = owned || (positioned && command.joints[j].owned);
  }
  return owned;
}

}  // namespace robotd::driver
