#include "driver/xarm_fault.hpp"

#include <string>

#include "codec/xarm_codec.hpp"

namespace robotd::xarm {

driver::FaultInfo arm_fault(int error_code, const driver::FaultInfo& servo_fault) {
  if (error_code == 0 || is_estop_error(error_code)) return servo_fault;
  driver::FaultInfo fault;
  fault.set(error_code, controller_error_text(error_code).c_str());
  return fault;
}

}  // namespace robotd::xarm
