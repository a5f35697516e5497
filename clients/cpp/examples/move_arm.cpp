// Acquire the simulated arm, move it, print its joint states, release it.
//
//   build/bin/robotd --config config/robotd.json &      # robotd with the simulated robots
//   build/bin/robotd_example_move_arm                     # this program
#include <chrono>
#include <cmath>
#include <cstdio>
#include <robotd/client.hpp>
#include <thread>
#include <vector>

int main() {
  using namespace std::chrono_literals;

  auto client = robotd::Client::connect();
  if (!client) {
    std::fprintf(stderr, "cannot join DDS: %s\n", client.error().message.c_str());
    return 1;
  }
  // Every motor of "arm"; if this program stops sending for 500 ms, robotd damps the arm.
  robotd::SessionRequest request;
  request.device = "arm";
  request.mode = robotd::ControlMode::kPosition;
  request.on_timeout = robotd::Behavior::kDamping;
  request.timeout = 500ms;
  auto session = client.value().request_control(request);
  if (!session) {
    std::fprintf(stderr, "no control: %s\n", session.error().message.c_str());
    return 1;
  }
  std::printf("session %s on %zu motors\n", session.value().session_id().c_str(), session.value().motor_ids().size());

  const auto start = client.value().next_joint_state("arm", 2s);
  if (!start) {
    std::fprintf(stderr, "%s\n", start.error().message.c_str());
    return 1;
  }

  // Stream a smooth 2-second move (cosine blend) of every joint by +0.5 rad, at 100 Hz.
  // robotd rate-limits and interpolates it into its 1 kHz loop.
  const std::size_t joints = session.value().motor_ids().size();
  constexpr double kMove_rad = 0.5;
  constexpr auto kDuration = 2s;
  const auto t0 = std::chrono::steady_clock::now();
  for (auto now = t0; now - t0 <= kDuration; now = std::chrono::steady_clock::now()) {
    const double s = std::chrono::duration<double>(now - t0) / kDuration;
    const double blend = 0.5 - 0.5 * std::cos(M_PI * s);
    std::vector<float> positions(joints);
    for (std::size_t j = 0; j < joints; ++j) {
      positions[j] = static_cast<float>(start.value().position[j] + kMove_rad * blend);
    }
    if (auto sent = session.value().send_positions(positions); !sent) {
      std::fprintf(stderr, "%s\n", sent.error().message.c_str());
      return 1;
    }
    std::this_thread::sleep_for(10ms);
  }
  // Hold the final target a moment, then print where the arm is.
  for (int i = 0; i < 30; ++i) {
    (void)session.value().keepalive();
    std::this_thread::sleep_for(10ms);
  }
  const auto end = client.value().next_joint_state("arm", 2s);
  if (!end) return 1;
  for (std::size_t j = 0; j < joints; ++j) {
    std::printf("%-8s %+.3f rad -> %+.3f rad  (%.3f N·m)\n", end.value().name[j].c_str(), start.value().position[j],
                end.value().position[j], end.value().effort[j]);
  }
  auto released = session.value().release(robotd::Behavior::kKeep);
  std::printf("%s\n", released ? released.value().message.c_str() : released.error().message.c_str());
  return released ? 0 : 1;
}
