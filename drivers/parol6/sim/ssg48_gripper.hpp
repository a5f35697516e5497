// The SSG-48 electric gripper on the board's CAN bus (spec §8), as the board sees it: it takes
// calibrate, clear-error and data-pack messages and answers polls and data packs with its
// position, motor current and status byte (hardware packing, §8.3).
//
// Model: it moves only once calibrated and activated, toward the commanded position at
// 25 + speed units/s (speed 0 … 255: about 10 s to 0.9 s for the full 0 … 255 stroke).
// Calibration takes 0.5 s and ends open (position 0), calibrated and activated. An E-stop bit
// in a data pack latches the E-stop error; the control channel can raise the temperature and
// timeout errors; any latched error stops it until a clear-error. An object set
// through the control channel stops a closing move at its position ("object detected while
// closing", current = the commanded current). Current: ±commanded/4 while moving (+ closing),
// the commanded current while holding an object, 0 at rest.
#pragma once

#include <cstdint>
#include <optional>

#include "codec/parol6_frames.hpp"

namespace robotd::parol6::sim {

/// CAN command 60: what the gripper reports.
struct GripperAnswer {
  std::uint8_t position = 0;
  std::int16_t current_ma = 0;
  std::uint8_t status = 0;
};

class Ssg48Gripper {
 public:
  static constexpr std::uint8_t kNodeId = 0;  // the SSG-48's default CAN node id
  static constexpr double kCalibrationS = 0.5;

  /// CAN command 62: no answer.
  void calibrate();
  /// CAN command 1: clears the latched errors; no answer.
  void clear_error();
  /// CAN command 61 with 5 bytes; answers with 60.
  GripperAnswer data_pack(std::uint8_t position, std::uint8_t speed, std::int16_t current_ma, std::uint8_t command);
  /// CAN command 61 with no data (a poll); answers with 60.
  GripperAnswer answer() const;

  void step(double dt_s);

  /// Raises the temperature and/or timeout error (latched until a clear-error), as a fault would.
  void raise_errors(bool temperature, bool timeout);
  /// A simulated object at `position` (0 … 255) that a closing move stops at; nullopt: none.
  void set_object(std::optional<std::uint8_t> position) { object_ = position; }

  double position() const { return position_; }
  std::uint8_t target() const { return target_; }
  std::uint8_t speed() const { return speed_; }
  std::int16_t current_setting_ma() const { return current_setting_ma_; }
  std::int16_t current_ma() const;
  std::uint8_t status() const;
  bool activated() const { return activated_; }
  bool calibrated() const { return calibrated_; }
  bool calibrating() const { return calibration_left_s_ > 0; }
  bool moving() const { return moving_; }
  bool estop_error() const { return estop_error_; }
  bool temperature_error() const { return temperature_error_; }
  bool timeout_error() const { return timeout_error_; }
  bool any_error() const { return estop_error_ || temperature_error_ || timeout_error_; }
  ObjectDetection object_detection() const { return detection_; }
  std::optional<std::uint8_t> object() const { return object_; }

 private:
  double position_ = 0;
  std::uint8_t target_ = 0;
  std::uint8_t speed_ = 0;
  std::int16_t current_setting_ma_ = 0;
  bool activated_ = false;
  bool calibrated_ = false;
  double calibration_left_s_ = 0;
  bool moving_ = false;
  bool closing_ = false;
  bool holding_object_ = false;
  bool estop_error_ = false;
  bool temperature_error_ = false;
  bool timeout_error_ = false;
  ObjectDetection detection_ = ObjectDetection::kMoving;
  std::optional<std::uint8_t> object_;
};

}  // namespace robotd::parol6::sim
