// Seeded random scenarios: a random device, then ticks interleaved with everything that can
// happen around a robot — clients that stream, pause, vanish and send garbage, e-stops,
// faults, lost links, strange feedback, maintenance and shutdown — at rates that make each
// of them happen several times in a few thousand ticks.
#pragma once

#include <cstdint>

#include "scenario.hpp"

namespace robotd::safety {

Scenario generate_scenario(std::uint64_t seed, std::size_t ticks);

}  // namespace robotd::safety
