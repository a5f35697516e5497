#include "ssg48_gripper.hpp"

#include <algorithm>
#include <cmath>

namespace robotd::parol6::sim {
namespace {

constexpr double kMinRate = 25;  // units/s at speed 0; + 1 unit/s per speed step
constexpr int kMovingCurrentDivider = 4;

}  // namespace

void Ssg48Gripper::calibrate() {
  calibration_left_s_ = kCalibrationS;
  moving_ = false;
  holding_object_ = false;
  detection_ = ObjectDetection::kMoving;
}

void Ssg48Gripper::clear_error() {
  estop_error_ = false;
  temperature_error_ = false;
  timeout_error_ = false;
}

void Ssg48Gripper::raise_errors(bool temperature, bool timeout) {
  temperature_error_ = temperature_error_ || temperature;
  timeout_error_ = timeout_error_ || timeout;
  if (any_error()) moving_ = false;
}

GripperAnswer Ssg48Gripper::data_pack(std::uint8_t position, std::uint8_t speed, std::int16_t current_ma,
                                      std::uint8_t command) {
  speed_ = speed;
  current_setting_ma_ = current_ma;
  activated_ = (command & gripper_command::kActivate) != 0;
  if ((command & gripper_command::kEstop) != 0) estop_error_ = true;
  if (!activated_ || any_error()) {
    moving_ = false;  // holds where it is
  } else if ((command & gripper_command::kMove) != 0 && calibrated_ && !calibrating()) {
    target_ = position;
    if (std::lround(position_) != target_ || !holding_object_) {
      closing_ = target_ > position_;
      holding_object_ = false;
      moving_ = true;
      detection_ = ObjectDetection::kMoving;
    }
  }
  return answer();
}

GripperAnswer Ssg48Gripper::answer() const {
  return GripperAnswer{
      .position = static_cast<std::uint8_t>(std::lround(position_)), .current_ma = current_ma(), .status = status()};
}

void Ssg48Gripper::step(double dt_s) {
  if (calibrating()) {
    calibration_left_s_ -= dt_s;
    if (calibration_left_s_ <= 0) {
      calibration_left_s_ = 0;
      calibrated_ = true;
      activated_ = true;
      position_ = 0;
      target_ = 0;
      detection_ = ObjectDetection::kAtPosition;
    }
    return;
  }
  if (!moving_) return;
  const double travel = (kMinRate + speed_) * dt_s;
  const double target = target_;
  if (closing_) {
    const double next = position_ + travel;
    if (object_ && *object_ >= position_ && *object_ < target && next >= *object_) {
      position_ = *object_;
      moving_ = false;
      holding_object_ = true;
      detection_ = ObjectDetection::kClosingOnObject;
      return;
    }
    position_ = std::min(next, target);
  } else {
    position_ = std::max(position_ - travel, target);
  }
  if (position_ == target) {
    moving_ = false;
    detection_ = ObjectDetection::kAtPosition;
  }
}

std::int16_t Ssg48Gripper::current_ma() const {
  if (!activated_) return 0;
  if (holding_object_) return current_setting_ma_;
  if (!moving_) return 0;
  const int magnitude = current_setting_ma_ / kMovingCurrentDivider;
  return static_cast<std::int16_t>(closing_ ? magnitude : -magnitude);
}

std::uint8_t Ssg48Gripper::status() const {
  unsigned bits = 0;
  if (activated_) bits |= gripper_status::kActivated;
  if (moving_) bits |= gripper_status::kMoving;
  const auto code = static_cast<unsigned>(detection_);
  if ((code & 1U) != 0) bits |= gripper_status::kObjectBit0;
  if ((code & 2U) != 0) bits |= gripper_status::kObjectBit1;
  if (temperature_error_) bits |= gripper_status::kTemperatureError;
  if (timeout_error_) bits |= gripper_status::kTimeoutError;
  if (estop_error_) bits |= gripper_status::kEstopError;
  if (calibrated_) bits |= gripper_status::kCalibrated;
  return static_cast<std::uint8_t>(bits);
}

}  // namespace robotd::parol6::sim
