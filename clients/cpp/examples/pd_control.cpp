// Closed-loop PD control of the simulated arm through robotd: each tick's state (position q,
// velocity dq) comes to the law, whose torques tau = kp (q_ref - q) - kd dq answer it and are
// applied on the next tick.
//
//   build/bin/robotd --config config/robotd.json &      # robotd with the simulated robots
//   build/bin/robotd_example_pd_control                   # this program
#include <chrono>
#include <cstdio>
#include <robotd/client.hpp>
#include <vector>

int main() {
  using namespace std::chrono_literals;
  constexpr double kStep_rad = 0.3;  // each joint's reference: where it started + 0.3 rad
  constexpr double kKp = 20.0;       // N·m/rad: with the sim arm's 0.05 kg·m², about 3 Hz
  constexpr double kKd = 1.0;        // N·m·s/rad: damped (ζ ≈ 0.65 with the joint's own damping)

  auto client = robotd::Client::connect();
  if (!client) {
    std::fprintf(stderr, "cannot join DDS: %s\n", client.error().message.c_str());
    return 1;
  }
  // Torques for every motor of "arm"; robotd damps the arm if the answers stop for 500 ms, and
  // warns when fewer than 95 % of the last 100 ticks were answered in time.
  robotd::SessionRequest request;
  request.device = "arm";
  request.mode = robotd::ControlMode::kTorque;
  request.on_timeout = robotd::Behavior::kDamping;
  request.timeout = 500ms;
  request.on_release = robotd::Behavior::kDamping;
  request.closed_loop = true;
  request.min_command_success_rate = 0.95F;
  request.on_low_success_rate = robotd::LowRateAction::kWarn;
  auto session = client.value().request_control(request);
  if (!session) {
    std::fprintf(stderr, "no control: %s\n", session.error().message.c_str());
    return 1;
  }

  std::vector<double> reference;  // rad, set from the first tick
  const auto report = session.value().run_control_loop(
      [&](const robotd::TickState& state) {
        if (reference.empty()) {
          for (const double q : state.position) reference.push_back(q + kStep_rad);
        }
        robotd::Command command;
        for (std::size_t j = 0; j < state.position.size(); ++j) {
          command.torques.push_back(
              static_cast<float>(kKp * (reference[j] - state.position[j]) - kKd * state.velocity[j]));
        }
        return command;  // command.finished = true would make this the last answer
      },
      {.duration = 3s});
  if (!report) {
    std::fprintf(stderr, "control loop: %s\n", report.error().message.c_str());
    return 1;
  }
  std::printf("%llu ticks answered (ticks %llu..%llu, %llu skipped)\n",
              static_cast<unsigned long long>(report.value().ticks_answered),
              static_cast<unsigned long long>(report.value().first_tick),
              static_cast<unsigned long long>(report.value().last_tick),
              static_cast<unsigned long long>(report.value().ticks_skipped));
  if (const auto last = session.value().next_tick(1s)) {
    for (std::size_t j = 0; j < last.value().position.size(); ++j) {
      std::printf("joint %zu: %+.3f rad (reference %+.3f)\n", j + 1, last.value().position[j], reference[j]);
    }
  }
  if (const auto info = session.value().info(2s)) {
    std::printf("robotd: %llu of %llu ticks answered in time (command success rate %.1f %%)\n",
                static_cast<unsigned long long>(info.value().ticks_answered_in_time),
                static_cast<unsigned long long>(info.value().ticks_to_answer),
                100.0 * info.value().command_success_rate);
  }
  return 0;  // the session's destructor releases the arm (on_release: DAMPING)
}
