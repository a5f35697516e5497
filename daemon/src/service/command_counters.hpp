// Per-device command counters, bumped by the intake thread and read by the status publisher.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

#include "control/command_validator.hpp"
#include "robotd/messages.hpp"

namespace robotd::service {

struct CommandCounterSet {
  std::atomic<std::uint64_t> received{0};
  std::atomic<std::uint64_t> accepted{0};
  std::atomic<std::uint64_t> clamped{0};
  std::array<std::atomic<std::uint64_t>, control::kRejectionCount> rejected{};

  void count_rejection(control::Rejection reason) {
    rejected[static_cast<std::size_t>(reason)].fetch_add(1, std::memory_order_relaxed);
  }

  /// The counters as DeviceStatus carries them; `dropped_stale` comes from the loop.
  CommandCounters snapshot(std::uint64_t dropped_stale) const {
    const auto get = [this](control::Rejection r) {
      return rejected[static_cast<std::size_t>(r)].load(std::memory_order_relaxed);
    };
    CommandCounters out;
    out.received = received.load(std::memory_order_relaxed);
    out.accepted = accepted.load(std::memory_order_relaxed);
    out.clamped = clamped.load(std::memory_order_relaxed);
    out.rejected_unknown_session = get(control::Rejection::kUnknownSession);
    out.rejected_wrong_device = get(control::Rejection::kWrongDevice);
    out.rejected_not_owner = get(control::Rejection::kNotOwner);
    out.rejected_unknown_motor = get(control::Rejection::kUnknownMotor);
    out.rejected_malformed = get(control::Rejection::kMalformed);
    out.rejected_non_finite = get(control::Rejection::kNonFinite);
    out.rejected_out_of_range = get(control::Rejection::kOutOfRange);
    out.rejected_estop = get(control::Rejection::kEstop);
    out.rejected_fault = get(control::Rejection::kFault);
    out.dropped_stale = dropped_stale;
    return out;
  }
};

}  // namespace robotd::service
