// robotctl's exit statuses and the one-line messages that go with failures.
#pragma once

#include <string>

#include "robotd/client/options.hpp"
#include "robotd/result.hpp"

namespace robotctl {

inline constexpr int kExitSuccess = 0;
inline constexpr int kExitFailure = 1;  // robotd refused, was not reachable, or the action did not complete
inline constexpr int kExitUsage = 2;    // the command line was wrong; nothing was asked of robotd

/// The shell convention for a process stopped by `signal_number` (130 for SIGINT).
inline int exit_status_for_signal(int signal_number) { return 128 + signal_number; }

/// Prints `error` as one line on stderr and returns kExitFailure. When robotd is not reachable
/// the line says where robotctl looked and how to start robotd; a refusal is robotd's own words.
int report_failure(const robotd::Error& error, const robotd::ClientOptions& options);
int report_failure(const std::string& message);
/// Prints what was expected on stderr and returns kExitUsage.
int report_usage_error(const std::string& message);

}  // namespace robotctl
