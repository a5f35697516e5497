// The Inspire EG2-4C2 two-finger gripper on the end board (spec §5.1, seed doc): an opening from
// 0 to 1000 that moves at 2 × speed units per second (speed 1000: the whole stroke in 0.5 s)
// within its route, stops on an object a test placed when closing, and reports the six modes.
#pragma once

#include <cstdint>
#include <optional>

#include <nlohmann/json.hpp>

namespace robotd::realman::sim {

class Gripper {
 public:
  enum class Mode : std::uint8_t {
    kOpenIdle = 1,     // at the route's max
    kClosedIdle = 2,   // at the route's min
    kStoppedIdle = 3,  // anywhere else
    kClosing = 4,
    kOpening = 5,
    kForceStopped = 6,  // closed on an object, holding it
  };
  static constexpr double kUnitsPerSecondPerSpeed = 2.0;

  /// set_gripper_route: the opening stays within [min, max] from now on.
  void set_route(int min, int max);
  /// set_gripper_release: opens to the route's max.
  void release(int speed);
  /// set_gripper_pick / set_gripper_pick_on: closes to the route's min, stopping on an object
  /// with `force` as the grip; `keep_gripping` closes again when the object goes.
  void pick(int speed, int force, bool keep_gripping);
  /// set_gripper_position: to `position` (clamped to the route) at the last speed; closing,
  /// an object stops it like a pick with the last force.
  void move_to(int position);

  /// An object between the fingers at `opening`: a closing motion stops there.
  void place_object(int opening);
  void remove_object();

  /// Runs the motion for `dt_s`; true when a motion ended during it (reached, or on an object).
  bool advance(double dt_s);

  int opening() const;
  Mode mode() const;
  int force_g() const { return holding() ? force_ : 0; }
  /// The get_gripper_state reply's fields (enable, status, error, mode, current_force,
  /// temperature, actpos).
  nlohmann::json state_fields() const;
  nlohmann::json control_state() const;  // for the control channel

 private:
  bool holding() const { return object_stop_ && !target_; }
  void start(double target, int speed);

  double opening_ = 1000;
  std::optional<double> target_;
  int route_min_ = 0;
  int route_max_ = 1000;
  int speed_ = 500;
  int force_ = 200;
  bool keep_gripping_ = false;
  bool object_stop_ = false;  // the last motion ended on the object
  std::optional<int> object_;
};

}  // namespace robotd::realman::sim
