// A device loop's tick phase (ticks are due at deadline + n × period, CLOCK_MONOTONIC) and when
// "send aligned" mode publishes against it.
#pragma once

#include <cstdint>

namespace robotd::detail {

struct TickPhase {
  std::int64_t deadline_steady_ns = 0;  // some tick's deadline
  std::int64_t period_ns = 0;           // 0 = unknown

  bool known() const { return period_ns > 0; }
};

/// The time to publish at so that a command is `lead_ns` ahead of a tick: the first tick due at or
/// after now + lead, minus the lead.
constexpr std::int64_t aligned_send_time_ns(TickPhase phase, std::int64_t now_ns, std::int64_t lead_ns) {
  const std::int64_t earliest_due = now_ns + lead_ns;
  const std::int64_t since_deadline = earliest_due - phase.deadline_steady_ns;
  std::int64_t periods = since_deadline / phase.period_ns;
  if (since_deadline % phase.period_ns != 0 && since_deadline > 0) ++periods;  // round up, towards the future
  return phase.deadline_steady_ns + periods * phase.period_ns - lead_ns;
}

}  // namespace robotd::detail
