#include "piper_sim_process.hpp"

#ifndef ROBOTD_PIPER_SIM
#error "ROBOTD_PIPER_SIM must point at the robotd-piper-sim executable"
#endif

namespace robotd::testing {

std::string PiperSimProcess::executable() { return ROBOTD_PIPER_SIM; }

PiperSimProcess::PiperSimProcess(std::string bus_path, std::vector<std::string> extra_args)
    : SimProcess(executable(), "piper", "--standin", bus_path.empty() ? unique_path("piper-bus") : std::move(bus_path),
                 std::move(extra_args)) {}

}  // namespace robotd::testing
