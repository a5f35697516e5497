#include "scenario.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

namespace robotd::safety {
namespace {

const char* field_name(FeedbackField field) {
  switch (field) {
    case FeedbackField::kPosition:
      return "position";
    case FeedbackField::kVelocity:
      return "velocity";
    case FeedbackField::kEffort:
      return "effort";
  }
  return "position";
}

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string motors_text(std::uint64_t motors) {
  std::string out;
  for (std::size_t j = 0; j < 64; ++j) {
    if ((motors >> j & 1U) != 0) out += (out.empty() ? "" : ",") + std::to_string(j);
  }
  return out.empty() ? "-" : out;
}

std::string number(double value) {
  std::array<char, 32> text{};
  const auto end = std::to_chars(text.data(), text.data() + text.size(), value).ptr;  // shortest exact
  return {text.data(), end};
}

// "newest", "newest-3", "newest+2": the tick a command answers, relative to the newest seen.
std::string answer_text(int offset) {
  return "newest" + (offset == 0 ? std::string() : (offset > 0 ? "+" : "") + std::to_string(offset));
}

int answer_offset_of(const std::string& text) {
  const std::string_view newest = "newest";
  const auto bad = [&text] {
    return std::invalid_argument("answers=" + text + " is not newest, newest-N or newest+N");
  };
  if (text.rfind(newest, 0) != 0) throw bad();
  if (text.size() == newest.size()) return 0;
  const char sign = text[newest.size()];
  if (sign != '+' && sign != '-') throw bad();
  const char* digits = text.data() + newest.size() + 1;
  int offset = 0;
  const auto [end, error] = std::from_chars(digits, text.data() + text.size(), offset);
  if (error != std::errc() || end != text.data() + text.size() || offset < 0) throw bad();
  return sign == '-' ? -offset : offset;
}

// One line's words after the first: "key=value" pairs and bare flags ("on", "off").
class Words {
 public:
  explicit Words(std::istringstream& line) {
    for (std::string word; line >> word;) {
      const auto equals = word.find('=');
      if (equals == std::string::npos) {
        flags_.push_back(word);
      } else {
        values_[word.substr(0, equals)] = word.substr(equals + 1);
      }
    }
  }

  bool has(const std::string& key) const { return values_.count(key) != 0; }
  const std::string& text(const std::string& key) const {
    const auto it = values_.find(key);
    if (it == values_.end()) throw std::invalid_argument("missing " + key + "=");
    return it->second;
  }
  template <class T>
  T integer(const std::string& key, T fallback) const {
    if (!has(key)) return fallback;
    T value{};
    const std::string& word = text(key);
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (error != std::errc() || end != word.data() + word.size())
      throw std::invalid_argument(key + "=" + word + " is not an integer");
    return value;
  }
  double real(const std::string& key, double fallback) const {
    if (!has(key)) return fallback;
    std::size_t used = 0;
    const double value = std::stod(text(key), &used);
    if (used != text(key).size()) throw std::invalid_argument(key + "=" + text(key) + " is not a number");
    return value;
  }
  bool flag(const std::string& yes, const std::string& no) const {
    for (const auto& word : flags_) {
      if (word == yes) return true;
      if (word == no) return false;
    }
    throw std::invalid_argument("expected '" + yes + "' or '" + no + "'");
  }

 private:
  std::map<std::string, std::string> values_;
  std::vector<std::string> flags_;
};

Behavior behavior_of(const std::string& text) {
  const auto behavior = parse_behavior(text);
  if (!behavior) throw std::invalid_argument("'" + text + "' is not keep, damping or zero_torque");
  return *behavior;
}

LowRateAction low_rate_action_of(const std::string& text) {
  const auto action = parse_low_rate_action(text);
  if (!action) throw std::invalid_argument("on_low='" + text + "' is not warn or fallback");
  return *action;
}

ControlMode mode_of(const std::string& text) {
  const auto mode = parse_control_mode(text);
  if (!mode) throw std::invalid_argument("'" + text + "' is not position, torque or mixed");
  return *mode;
}

std::uint64_t motors_of(const std::string& text) {
  std::uint64_t motors = 0;
  if (text == "-") return 0;
  std::istringstream list(text);
  for (std::string id; std::getline(list, id, ',');) {
    const int joint = std::stoi(id);
    if (joint < 0 || joint >= 64) throw std::invalid_argument("motor " + id + " is outside 0..63");
    motors |= std::uint64_t{1} << static_cast<unsigned>(joint);
  }
  return motors;
}

DeviceSpec parse_device(const Words& words) {
  DeviceSpec spec;
  spec.joints = words.integer<std::size_t>("joints", spec.joints);
  spec.torque = words.integer<int>("torque", 1) != 0;
  spec.damping = words.integer<int>("damping", 1) != 0;
  spec.zero_torque = words.integer<int>("zero_torque", 1) != 0;
  spec.safe = behavior_of(words.text("safe"));
  spec.shutdown = behavior_of(words.text("shutdown"));
  spec.policy = words.text("policy") == "clamp" ? control::LimitPolicy::kClamp : control::LimitPolicy::kReject;
  spec.feedback_timeout_ms = words.integer<int>("feedback_timeout_ms", spec.feedback_timeout_ms);
  spec.shutdown_ms = words.integer<int>("shutdown_ms", spec.shutdown_ms);
  spec.position_min = words.real("position_min", spec.position_min);
  spec.position_max = words.real("position_max", spec.position_max);
  spec.velocity_max = words.real("velocity_max", spec.velocity_max);
  spec.acceleration_max = words.real("acceleration_max", spec.acceleration_max);
  spec.effort_max = words.real("effort_max", spec.effort_max);
  spec.kp_max = words.real("kp_max", spec.kp_max);
  spec.kd_max = words.real("kd_max", spec.kd_max);
  spec.default_kp = words.real("default_kp", spec.default_kp);
  spec.default_kd = words.real("default_kd", spec.default_kd);
  if (spec.joints == 0 || spec.joints > 16) throw std::invalid_argument("joints must be 1..16");
  return spec;
}

Event parse_event(const std::string& keyword, const Words& words) {
  Event event;
  event.label = words.integer<int>("s", 0);
  if (keyword == "tick") {
    event.kind = Event::Kind::kTick;
    event.count = words.integer<int>("n", 1);
    event.latency_us = words.integer<int>("latency_us", 0);
  } else if (keyword == "start") {
    event.kind = Event::Kind::kStart;
    event.motors = motors_of(words.text("motors"));
    event.mode = mode_of(words.text("mode"));
    event.behavior = behavior_of(words.text("fallback"));
    event.timeout_ms = words.integer<int>("timeout_ms", 100);
    event.default_kp = words.real("default_kp", -1);
    event.default_kd = words.real("default_kd", -1);
    event.min_rate = words.real("min_rate", 0);
    if (words.has("on_low")) event.on_low = low_rate_action_of(words.text("on_low"));
  } else if (keyword == "release") {
    event.kind = Event::Kind::kRelease;
    event.behavior = behavior_of(words.text("mode"));
  } else if (keyword == "command") {
    event.kind = Event::Kind::kCommand;
    event.seed = words.integer<std::uint32_t>("seed", 0);
    event.answers = words.has("answers");
    if (event.answers) event.answer_offset = answer_offset_of(words.text("answers"));
  } else if (keyword == "keepalive") {
    event.kind = Event::Kind::kKeepalive;
  } else if (keyword == "estop") {
    event.kind = Event::Kind::kEstop;
    event.on = words.flag("engage", "reset");
  } else if (keyword == "estop_input") {
    event.kind = Event::Kind::kEstopInput;
    event.on = words.flag("pressed", "released");
  } else if (keyword == "fault") {
    event.kind = Event::Kind::kFault;
    event.code = words.integer<int>("code", 1);
  } else if (keyword == "link") {
    event.kind = Event::Kind::kLink;
    event.on = words.flag("up", "down");
  } else if (keyword == "silence") {
    event.kind = Event::Kind::kSilence;
    event.on = words.flag("on", "off");
  } else if (keyword == "nonfinite") {
    event.kind = Event::Kind::kNonFinite;
    event.joint = words.integer<std::size_t>("joint", 0);
    const std::string& field = words.text("field");
    event.field = field == "velocity" ? FeedbackField::kVelocity
                                      : (field == "effort" ? FeedbackField::kEffort : FeedbackField::kPosition);
    event.on = words.flag("on", "off");
  } else if (keyword == "teleport") {
    event.kind = Event::Kind::kTeleport;
    event.joint = words.integer<std::size_t>("joint", 0);
    event.value = words.real("position", 0);
  } else if (keyword == "narrow") {
    event.kind = Event::Kind::kNarrow;
    event.joint = words.integer<std::size_t>("joint", 0);
    event.value = words.real("range", 1);
  } else if (keyword == "recover" || keyword == "reset_zero") {
    event.kind = keyword == "recover" ? Event::Kind::kRecover : Event::Kind::kResetZero;
    event.count = words.integer<int>("ticks", 1);
    event.fail = words.integer<int>("fail", 0) != 0;
  } else if (keyword == "shutdown") {
    event.kind = Event::Kind::kShutdown;
  } else {
    throw std::invalid_argument("unknown event '" + keyword +
                                "' (expected tick, start, release, command, keepalive, estop, estop_input, fault, "
                                "link, silence, nonfinite, teleport, narrow, recover, reset_zero, shutdown)");
  }
  return event;
}

}  // namespace

control::DeviceModel DeviceSpec::model() const {
  control::DeviceModel model;
  model.name = "dev";
  model.driver = "plant";
  model.supports_torque = torque;
  model.behaviors = control::BehaviorSupport{damping, zero_torque};
  model.limit_policy = policy;
  for (std::size_t j = 0; j < joints; ++j) {
    model.joint_names.push_back("j" + std::to_string(j));
    driver::JointLimits limits;
    limits.position_min_rad = position_min;
    limits.position_max_rad = position_max;
    limits.velocity_max_rad_s = velocity_max;
    limits.acceleration_max_rad_s2 = acceleration_max;
    limits.effort_max_nm = effort_max;
    limits.kp_max = kp_max;
    limits.kd_max = kd_max;
    model.limits.push_back(limits);
    model.default_kp.push_back(default_kp);
    model.default_kd.push_back(default_kd);
    model.zero_position_rad.push_back(0);
  }
  return model;
}

std::size_t Scenario::tick_count() const {
  std::size_t ticks = 0;
  for (const auto& event : events) {
    if (event.kind == Event::Kind::kTick) ticks += static_cast<std::size_t>(event.count);
  }
  return ticks;
}

std::string to_text(const Event& e) {
  const std::string session = " s=" + std::to_string(e.label);
  switch (e.kind) {
    case Event::Kind::kTick:
      return "tick n=" + std::to_string(e.count) +
             (e.latency_us != 0 ? " latency_us=" + std::to_string(e.latency_us) : "");
    case Event::Kind::kStart:
      return "start" + session + " motors=" + motors_text(e.motors) + " mode=" + lower(to_string(e.mode)) +
             " fallback=" + lower(to_string(e.behavior)) + " timeout_ms=" + std::to_string(e.timeout_ms) +
             (e.default_kp >= 0 ? " default_kp=" + number(e.default_kp) : "") +
             (e.default_kd >= 0 ? " default_kd=" + number(e.default_kd) : "") +
             (e.min_rate != 0 ? " min_rate=" + number(e.min_rate) : "") +
             (e.on_low != LowRateAction::kWarn ? " on_low=" + lower(to_string(e.on_low)) : "");
    case Event::Kind::kRelease:
      return "release" + session + " mode=" + lower(to_string(e.behavior));
    case Event::Kind::kCommand:
      return "command" + session + " seed=" + std::to_string(e.seed) +
             (e.answers ? " answers=" + answer_text(e.answer_offset) : "");
    case Event::Kind::kKeepalive:
      return "keepalive" + session;
    case Event::Kind::kEstop:
      return std::string("estop ") + (e.on ? "engage" : "reset");
    case Event::Kind::kEstopInput:
      return std::string("estop_input ") + (e.on ? "pressed" : "released");
    case Event::Kind::kFault:
      return "fault code=" + std::to_string(e.code);
    case Event::Kind::kLink:
      return std::string("link ") + (e.on ? "up" : "down");
    case Event::Kind::kSilence:
      return std::string("silence ") + (e.on ? "on" : "off");
    case Event::Kind::kNonFinite:
      return "nonfinite joint=" + std::to_string(e.joint) + " field=" + field_name(e.field) + (e.on ? " on" : " off");
    case Event::Kind::kTeleport:
      return "teleport joint=" + std::to_string(e.joint) + " position=" + number(e.value);
    case Event::Kind::kNarrow:
      return "narrow joint=" + std::to_string(e.joint) + " range=" + number(e.value);
    case Event::Kind::kRecover:
      return "recover ticks=" + std::to_string(e.count) + " fail=" + (e.fail ? "1" : "0");
    case Event::Kind::kResetZero:
      return "reset_zero ticks=" + std::to_string(e.count);
    case Event::Kind::kShutdown:
      return "shutdown";
  }
  return "";
}

std::string to_text(const Scenario& scenario) {
  const DeviceSpec& d = scenario.device;
  std::ostringstream out;
  out << "device joints=" << d.joints << " torque=" << d.torque << " damping=" << d.damping
      << " zero_torque=" << d.zero_torque << " safe=" << lower(to_string(d.safe))
      << " shutdown=" << lower(to_string(d.shutdown))
      << " policy=" << (d.policy == control::LimitPolicy::kClamp ? "clamp" : "reject")
      << " feedback_timeout_ms=" << d.feedback_timeout_ms << " shutdown_ms=" << d.shutdown_ms
      << " position_min=" << number(d.position_min) << " position_max=" << number(d.position_max)
      << " velocity_max=" << number(d.velocity_max) << " acceleration_max=" << number(d.acceleration_max)
      << " effort_max=" << number(d.effort_max) << " kp_max=" << number(d.kp_max) << " kd_max=" << number(d.kd_max)
      << " default_kp=" << number(d.default_kp) << " default_kd=" << number(d.default_kd) << "\n";
  for (const auto& event : scenario.events) out << to_text(event) << "\n";
  return out.str();
}

std::optional<Scenario> parse_scenario(std::string_view text, std::string& error) {
  Scenario scenario;
  bool have_device = false;
  std::istringstream lines{std::string(text)};
  int number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words_in(line);
    std::string keyword;
    if (!(words_in >> keyword)) continue;
    try {
      const Words words(words_in);
      if (keyword == "device") {
        scenario.device = parse_device(words);
        have_device = true;
      } else {
        if (!have_device) throw std::invalid_argument("the first line must be 'device ...'");
        scenario.events.push_back(parse_event(keyword, words));
      }
    } catch (const std::exception& e) {
      error = "line " + std::to_string(number) + ": " + e.what();
      return std::nullopt;
    }
  }
  if (!have_device) {
    error = "no 'device ...' line";
    return std::nullopt;
  }
  return scenario;
}

}  // namespace robotd::safety
