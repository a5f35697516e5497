#include "gripper.hpp"

#include <algorithm>
#include <cmath>

namespace robotd::realman::sim {
namespace {

constexpr int kTemperatureC = 40;

}  // namespace

void Gripper::set_route(int min, int max) {
  route_min_ = min;
  route_max_ = max;
}

void Gripper::start(double target, int speed) {
  speed_ = speed;
  target_ = std::clamp(target, static_cast<double>(route_min_), static_cast<double>(route_max_));
  object_stop_ = false;
}

void Gripper::release(int speed) {
  keep_gripping_ = false;
  start(route_max_, speed);
}

void Gripper::pick(int speed, int force, bool keep_gripping) {
  force_ = force;
  keep_gripping_ = keep_gripping;
  start(route_min_, speed);
}

void Gripper::move_to(int position) {
  keep_gripping_ = false;
  start(position, speed_);
}

void Gripper::place_object(int opening) { object_ = opening; }

void Gripper::remove_object() {
  object_.reset();
  if (!holding()) return;
  object_stop_ = false;
  if (keep_gripping_) target_ = route_min_;  // pick_on: the grip is lost, close again
}

bool Gripper::advance(double dt_s) {
  if (!target_) return false;
  const double step = kUnitsPerSecondPerSpeed * speed_ * dt_s;
  if (*target_ > opening_) {
    opening_ = std::min(*target_, opening_ + step);
  } else {
    const double stop_at = object_ && *object_ <= opening_ ? std::max<double>(*target_, *object_) : *target_;
    opening_ = std::max(stop_at, opening_ - step);
    if (opening_ == stop_at && stop_at > *target_) {
      object_stop_ = true;
      target_.reset();
      return true;
    }
  }
  if (opening_ != *target_) return false;
  target_.reset();
  return true;
}

int Gripper::opening() const { return static_cast<int>(std::lround(opening_)); }

Gripper::Mode Gripper::mode() const {
  if (target_) return *target_ < opening_ ? Mode::kClosing : Mode::kOpening;
  if (object_stop_) return Mode::kForceStopped;
  if (opening() >= route_max_) return Mode::kOpenIdle;
  if (opening() <= route_min_) return Mode::kClosedIdle;
  return Mode::kStoppedIdle;
}

nlohmann::json Gripper::state_fields() const {
  return {{"enable", 1},
          {"status", 1},
          {"error", 0},
          {"mode", static_cast<int>(mode())},
          {"current_force", force_g()},
          {"temperature", kTemperatureC},
          {"actpos", opening()}};
}

nlohmann::json Gripper::control_state() const {
  return {{"opening", opening_},
          {"target", target_ ? nlohmann::json(*target_) : nlohmann::json(nullptr)},
          {"mode", static_cast<int>(mode())},
          {"route", {route_min_, route_max_}},
          {"speed", speed_},
          {"force", force_},
          {"keep_gripping", keep_gripping_},
          {"force_g", force_g()},
          {"object", object_ ? nlohmann::json(*object_) : nlohmann::json(nullptr)}};
}

}  // namespace robotd::realman::sim
