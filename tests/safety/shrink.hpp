// Shrinks a failing scenario to a minimal one that still breaks the same invariant in the
// same way (the same reason, whatever its numbers): cut
// everything after the failure, remove chunks of events (delta debugging) while it still
// fails, then shorten each run of ticks. Bounded by a number of replays.
#pragma once

#include <cstddef>

#include "loop_rig.hpp"
#include "scenario.hpp"

namespace robotd::safety {

struct ShrinkResult {
  Scenario scenario;
  RunResult result;
  std::size_t replays = 0;
};

/// Shrinks `failing`, which `run` found to fail with `failure`.
ShrinkResult shrink(const Scenario& failing, const RunResult& failure, Runner run, std::size_t max_replays = 20000);

}  // namespace robotd::safety
