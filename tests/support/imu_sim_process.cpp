#include "imu_sim_process.hpp"

#ifndef ROBOTD_IMU_SIM
#error "ROBOTD_IMU_SIM must point at the robotd-imu-sim executable"
#endif

namespace robotd::testing {

std::string ImuSimProcess::executable() { return ROBOTD_IMU_SIM; }

ImuSimProcess::ImuSimProcess(std::string pty_path, std::vector<std::string> extra_args)
    : SimProcess(executable(), "imu", "--pty",
                 pty_path.empty() ? SimProcess::unique_path("imu-tty", "") : std::move(pty_path),
                 std::move(extra_args)) {}

}  // namespace robotd::testing
