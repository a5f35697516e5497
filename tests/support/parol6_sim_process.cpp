#include "parol6_sim_process.hpp"

#ifndef ROBOTD_PAROL6_SIM
#error "ROBOTD_PAROL6_SIM must point at the robotd-parol6-sim executable"
#endif

namespace robotd::testing {

std::string Parol6SimProcess::executable() { return ROBOTD_PAROL6_SIM; }

Parol6SimProcess::Parol6SimProcess(std::string pty_path, std::vector<std::string> extra_args)
    : SimProcess(executable(), "parol6", "--pty", pty_path.empty() ? unique_path("parol6-tty") : std::move(pty_path),
                 std::move(extra_args)) {}

}  // namespace robotd::testing
