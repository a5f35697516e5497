#include "scenario_generator.hpp"

#include <algorithm>
#include <optional>
#include <random>

namespace robotd::safety {
namespace {

class Dice {
 public:
  explicit Dice(std::uint64_t seed) : engine_(seed) {}

  bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(engine_) < p; }
  int between(int low, int high) { return std::uniform_int_distribution<int>(low, high)(engine_); }
  double real(double low, double high) { return std::uniform_real_distribution<double>(low, high)(engine_); }
  std::uint32_t word() { return static_cast<std::uint32_t>(engine_()); }
  template <class It>
  void shuffle(It first, It last) {
    std::shuffle(first, last, engine_);
  }
  template <class T>
  T pick(std::initializer_list<T> choices) {
    return *(choices.begin() + between(0, static_cast<int>(choices.size()) - 1));
  }

 private:
  std::mt19937_64 engine_;
};

DeviceSpec random_device(Dice& dice) {
  DeviceSpec spec;
  spec.joints = static_cast<std::size_t>(dice.between(1, 6));
  switch (dice.between(0, 2)) {
    case 0:  // a position-only arm: KEEP is all it can do
      spec.torque = false;
      spec.damping = false;
      spec.zero_torque = false;
      break;
    case 1:  // MIT motors
      break;
    default:  // can damp but not let go
      spec.zero_torque = false;
      break;
  }
  spec.safe = dice.pick({Behavior::kDamping, Behavior::kKeep, Behavior::kZeroTorque});
  spec.shutdown = dice.pick({Behavior::kDamping, Behavior::kKeep, Behavior::kZeroTorque});
  spec.policy = dice.chance(0.5) ? control::LimitPolicy::kClamp : control::LimitPolicy::kReject;
  spec.feedback_timeout_ms = dice.between(10, 100);
  spec.shutdown_ms = dice.between(5, 60);
  const double half_range = dice.real(0.5, 3.0);
  const double centre = dice.real(-0.5, 0.5);
  spec.position_min = centre - half_range;
  spec.position_max = centre + half_range;
  spec.velocity_max = dice.real(0.3, 4.0);
  spec.acceleration_max = dice.real(2.0, 40.0);
  spec.effort_max = dice.real(1.0, 20.0);
  spec.kp_max = dice.real(20.0, 300.0);
  spec.kd_max = dice.real(1.0, 20.0);
  spec.default_kp = dice.real(1.0, spec.kp_max);
  spec.default_kd = dice.real(0.2, spec.kd_max);
  return spec;
}

struct Client {
  int label = 0;
  bool streaming = true;
  std::uint64_t motors = 0;  // 0 = every motor
  Event request;             // its request_control, repeated when it comes back
  bool closed_loop = false;  // answers the newest state it has seen (a controller closing its loop)
  double send_chance = 0.9;  // a command on a tick: how often it keeps up
};

// A closed-loop client keeps up on nearly every tick, most ticks, or falls behind often; with
// the commands the device refuses, its success rate lands on either side of typical minimums.
void make_closed_loop(Client& client, Dice& dice) {
  client.closed_loop = true;
  client.send_chance = dice.pick({0.999, 0.97, 0.9, 0.7});
  if (dice.chance(0.7)) {
    client.request.min_rate = dice.between(40, 190) / 200.0;  // 0.2..0.95 in half percents
    client.request.on_low = dice.chance(0.5) ? LowRateAction::kFallback : LowRateAction::kWarn;
  }
}

// What a closed-loop client's command answers: mostly the newest state, now and then an older
// one, none, or (refused by the command gate) a tick that has not run yet.
void pick_answer(Event& command, Dice& dice) {
  const double draw = dice.real(0, 1);
  if (draw < 0.05) return;  // answers_tick 0
  command.answers = true;
  if (draw < 0.10) {
    command.answer_offset = -dice.between(1, 5);
  } else if (draw < 0.13) {
    command.answer_offset = dice.between(1, 3);
  }
}

}  // namespace

Scenario generate_scenario(std::uint64_t seed, std::size_t ticks) {
  Dice dice(seed);
  Scenario scenario;
  scenario.device = random_device(dice);
  const DeviceSpec& spec = scenario.device;
  auto& events = scenario.events;
  const auto push = [&events](Event event) { events.push_back(event); };

  std::vector<Client> clients;
  int next_label = 1;
  bool estop = false;
  bool estop_input = false;
  bool link_up = true;
  bool silent = false;
  bool faulty = false;          // something happened that a recover would clear
  std::optional<Event> glitch;  // a joint reading non-finite now
  std::size_t elapsed = 0;

  Event first_ticks;
  first_ticks.count = 3;
  push(first_ticks);
  elapsed += 3;

  while (elapsed < ticks) {
    const std::size_t window = events.size();  // what happens before the next tick, in any order
    // A new client asks for motors no other client of the scenario holds (the device refuses
    // if they are taken after all, or if it is not RUNNING).
    if (clients.size() < 3 && dice.chance(0.004)) {
      std::uint64_t taken = 0;
      for (const Client& client : clients) taken |= client.motors == 0 ? ~std::uint64_t{0} : client.motors;
      Client client;
      client.label = next_label++;
      for (std::size_t j = 0; j < spec.joints; ++j) {
        if ((taken >> j & 1U) == 0 && dice.chance(0.6)) client.motors |= std::uint64_t{1} << j;
      }
      Event& start = client.request;
      start.kind = Event::Kind::kStart;
      start.label = client.label;
      start.motors = client.motors;
      start.mode = spec.torque ? dice.pick({ControlMode::kPosition, ControlMode::kTorque, ControlMode::kMixed})
                               : ControlMode::kPosition;
      start.behavior = dice.pick({Behavior::kKeep, Behavior::kDamping, Behavior::kZeroTorque});
      start.timeout_ms = dice.chance(0.1) ? dice.between(500, 3000) : dice.between(10, 200);
      if (dice.chance(0.3)) start.default_kp = dice.real(0, spec.kp_max);
      if (dice.chance(0.3)) start.default_kd = dice.real(0, spec.kd_max);
      if (dice.chance(0.5)) {
        make_closed_loop(client, dice);
      } else if (dice.chance(0.1)) {  // a minimum asked for, but never closing the loop: never judged
        start.min_rate = 0.9;
        start.on_low = LowRateAction::kFallback;
      }
      push(start);
      clients.push_back(client);
    }
    // Clients stream (one command a tick, now and then a tick late or a burst), pause, return,
    // release or disappear; a client whose session ended keeps sending for a while.
    for (auto it = clients.begin(); it != clients.end();) {
      Client& client = *it;
      if (dice.chance(0.003)) client.streaming = !client.streaming;
      // A streaming client asks again now and then: its session may have ended (a timeout
      // during a fault or an e-stop). While the session lives, the device refuses the overlap.
      if (client.streaming && dice.chance(0.05)) push(client.request);
      if (client.streaming && dice.chance(client.send_chance)) {
        const int burst = dice.chance(0.02) ? dice.between(2, 5) : 1;
        for (int i = 0; i < burst; ++i) {
          Event command;
          command.kind = Event::Kind::kCommand;
          command.label = client.label;
          command.seed = dice.word();
          if (client.closed_loop) pick_answer(command, dice);
          push(command);
        }
      } else if (dice.chance(0.01)) {
        Event keepalive;
        keepalive.kind = Event::Kind::kKeepalive;
        keepalive.label = client.label;
        push(keepalive);
      }
      if (dice.chance(0.0008)) {
        Event release;
        release.kind = Event::Kind::kRelease;
        release.label = client.label;
        release.behavior = dice.pick({Behavior::kKeep, Behavior::kDamping, Behavior::kZeroTorque});
        push(release);
      }
      if (dice.chance(0.0008)) {
        it = clients.erase(it);
      } else {
        ++it;
      }
    }
    // The world around the robot.
    if (!estop && dice.chance(0.0006)) {
      estop = true;
      push(Event{.kind = Event::Kind::kEstop, .on = true});
    } else if (estop && dice.chance(0.006)) {
      estop = false;
      push(Event{.kind = Event::Kind::kEstop, .on = false});
    }
    if (!estop_input && dice.chance(0.00015)) {
      estop_input = true;
      push(Event{.kind = Event::Kind::kEstopInput, .on = true});
    } else if (estop_input && dice.chance(0.01)) {
      estop_input = false;
      push(Event{.kind = Event::Kind::kEstopInput, .on = false});
    }
    if (dice.chance(0.0003)) {
      faulty = true;
      push(Event{.kind = Event::Kind::kFault, .code = dice.between(1, 99)});
    }
    if (link_up && dice.chance(0.0003)) {
      link_up = false;
      faulty = true;
      push(Event{.kind = Event::Kind::kLink, .on = false});
    } else if (!link_up && dice.chance(0.01)) {
      link_up = true;
      push(Event{.kind = Event::Kind::kLink, .on = true});
    }
    if (!silent && dice.chance(0.0003)) {
      silent = true;
      faulty = true;
      push(Event{.kind = Event::Kind::kSilence, .on = true});
    } else if (silent && dice.chance(0.02)) {
      silent = false;
      push(Event{.kind = Event::Kind::kSilence, .on = false});
    }
    // A joint reads NaN or Inf for a while: sometimes a glitch, sometimes long enough to fault.
    if (!glitch && dice.chance(0.0008)) {
      glitch = Event{.kind = Event::Kind::kNonFinite, .on = true};
      glitch->joint = static_cast<std::size_t>(dice.between(0, static_cast<int>(spec.joints) - 1));
      glitch->field = dice.pick({FeedbackField::kPosition, FeedbackField::kVelocity, FeedbackField::kEffort});
      push(*glitch);
      faulty = true;
    } else if (glitch && dice.chance(0.03)) {
      glitch->on = false;
      push(*glitch);
      glitch.reset();
    }
    if (dice.chance(0.0004)) {
      Event moved;
      moved.kind = Event::Kind::kTeleport;
      moved.joint = static_cast<std::size_t>(dice.between(0, static_cast<int>(spec.joints) - 1));
      moved.value = dice.real(spec.position_min - 1.0, spec.position_max + 1.0);
      push(moved);
    }
    // The device's limits narrow while it runs (an op, a reconnect reading the arm's limits).
    if (dice.chance(0.0002)) {
      Event narrow;
      narrow.kind = Event::Kind::kNarrow;
      narrow.joint = static_cast<std::size_t>(dice.between(0, static_cast<int>(spec.joints) - 1));
      narrow.value = dice.real(0.1, spec.position_max);
      push(narrow);
    }
    // Someone calls recover: mostly after something went wrong, now and then on a healthy device.
    if (dice.chance(faulty ? 0.02 : 0.0002)) {
      Event recover;
      recover.kind = Event::Kind::kRecover;
      recover.count = dice.chance(0.05) ? dice.between(500, 2000) : dice.between(1, 100);
      recover.fail = dice.chance(0.2);
      faulty = faulty && (recover.fail || !link_up || silent || glitch.has_value() || dice.chance(0.5));
      push(recover);
    }
    if (dice.chance(0.0002)) {
      Event zero;
      zero.kind = Event::Kind::kResetZero;
      zero.count = dice.between(1, 500);
      push(zero);
    }

    dice.shuffle(events.begin() + static_cast<std::ptrdiff_t>(window), events.end());

    // SIGTERM, now and then in the middle of everything (the scenario ends with the shutdown stop).
    if (dice.chance(0.00005)) break;

    // The next tick, usually on time; sometimes late, now and then stalled for many periods.
    Event tick;
    if (dice.chance(0.01)) {
      tick.latency_us = dice.between(200, 900);
    } else if (dice.chance(0.001)) {
      tick.latency_us = dice.between(1000, 40000);
    } else {
      tick.latency_us = dice.chance(0.5) ? 0 : dice.between(1, 100);
    }
    if (!events.empty() && events.back().kind == Event::Kind::kTick && events.back().latency_us == tick.latency_us) {
      ++events.back().count;
    } else {
      push(tick);
    }
    ++elapsed;
  }
  if (elapsed < ticks || dice.chance(0.5)) {
    push(Event{.kind = Event::Kind::kShutdown});
    Event tail;
    tail.count = spec.shutdown_ms + 5;
    push(tail);
  }
  return scenario;
}

}  // namespace robotd::safety
