// What robotctl replay prints before it moves anything (and all that --dry-run prints): the
// recording, what the replay would do per motor, and every violation of the device's limits.
#pragma once

#include <string>

#include "recording/recording_format.hpp"
#include "recording/replay_plan.hpp"

namespace robotctl {

std::string replay_report(const std::string& path, const recording::Description& description,
                          const recording::ReplayPlan& plan, const recording::ReplayCheck& check,
                          const std::string& device, double speed);

}  // namespace robotctl
