#include "dds/state_publisher.hpp"

#include <cmath>

#include <spdlog/spdlog.h>

#include "app/log_text.hpp"
#include "dds/yesense_imu.hpp"
#include "rt/monotonic_clock.hpp"
#include "rt/realtime_thread.hpp"

namespace robotd::dds {
namespace {

std::string state_text(const device::LoopState& state, const std::string& estop_note) {
  std::string text(to_string(state.state));
  if (state.state == DeviceState::kFault) text += ": " + std::string(state.fault.text.data());
  if (state.estop && !estop_note.empty()) text += " (e-stop " + estop_note + ")";
  return text;
}

const char* session_end_text(device::LoopEvent::Type type) {
  switch (type) {
    case device::LoopEvent::Type::kSessionTimedOut:
      return "timed out";
    case device::LoopEvent::Type::kSessionReleased:
      return "released";
    case device::LoopEvent::Type::kSessionEndedByShutdown:
      return "ended by shutdown";
    case device::LoopEvent::Type::kSessionRateTooLow:
      return "ended: its command success rate fell below its minimum";
    default:
      return "ended";
  }
}

}  // namespace

StatePublisher::StatePublisher(device::Device& device, std::size_t device_index, StateWriters writers,
                               service::SessionService& sessions, const service::CommandCounterSet& counters,
                               device::BlackBox& black_box, const config::DaemonConfig& daemon)
    : device_(device),
      device_index_(device_index),
      writers_(writers),
      sessions_(sessions),
      counters_(counters),
      black_box_(black_box),
      daemon_(daemon),
      window_(static_cast<std::size_t>(daemon.stats_window_ticks)) {
  const auto& model = device.model();
  joint_state_.header.frame_id = model.name;
  joint_state_.name = model.joint_names;
  joint_state_.position.resize(model.joint_count());
  joint_state_.velocity.resize(model.joint_count());
  joint_state_.effort.resize(model.joint_count());
  tick_state_.header.frame_id = model.name;
  tick_state_.position.resize(model.joint_count());
  tick_state_.velocity.resize(model.joint_count());
  tick_state_.effort.resize(model.joint_count());
}

StatePublisher::~StatePublisher() {
  stopping_.store(true);
  device_.channel().state_ready.notify();
  if (thread_.joinable()) thread_.join();
}

void StatePublisher::start() {
  thread_ = driver::NamedThread("pub-" + device_.model().name, [this] {
    (void)rt::run_current_thread_fifo(daemon_.loop_io_priority);
    run();
  });
}

void StatePublisher::run() {
  const std::int64_t status_period_ns = rt::kNsPerSecond / daemon_.status_rate_hz;
  rt::TickSignal& ticks = device_.channel().state_ready;
  std::int64_t next_status = rt::monotonic_now_ns();
  std::uint32_t seen = ticks.count();
  while (!stopping_.load()) {
    // Woken by the loop's next tick; the timeout keeps /device_status going while it does not tick.
    ticks.wait(seen, std::max<std::int64_t>(next_status - rt::monotonic_now_ns(), 0));
    seen = ticks.count();
    drain_loop(true);
    const std::int64_t now = rt::monotonic_now_ns();
    if (now >= next_status) {
      publish_device_status();
      next_status = now + status_period_ns;
    }
  }
}

void StatePublisher::finish() {
  stopping_.store(true);
  device_.channel().state_ready.notify();
  if (thread_.joinable()) thread_.join();
  drain_loop(false);
  publish_device_status();
  writers_.device_status->wait_for_acks(DDS_MSECS(500));
}

void StatePublisher::drain_loop(bool publish_states) {
  device::DeviceChannel& channel = device_.channel();
  {
    const std::lock_guard lock(window_mutex_);
    while (auto timing = channel.timings.pop()) window_.add(*timing);
  }
  while (auto event = channel.loop_events.pop()) handle(*event);
  // With a state every tick, the newest state is the one to publish; with one every N ticks, the
  // newest due one (the loop keeps it apart, so a late wake-up does not lose it to a newer tick).
  const bool every_tick = device::state_every_ticks(device_.config()) == 1;
  if (const device::LoopState* state = channel.state.take()) {
    {
      const std::lock_guard lock(latest_mutex_);
      latest_ = *state;
    }
    if (publish_states) {
      if (every_tick) publish_state(*state);
      publish_end_pose(*state);
    }
  }
  if (const device::LoopState* due = every_tick ? nullptr : channel.due_state.take();
      due != nullptr && publish_states) {
    publish_state(*due);
  }
}

void StatePublisher::handle(const device::LoopEvent& event) {
  const std::string& name = device_.model().name;
  switch (event.type) {
    case device::LoopEvent::Type::kSessionTimedOut:
    case device::LoopEvent::Type::kSessionReleased:
    case device::LoopEvent::Type::kSessionEndedByShutdown:
    case device::LoopEvent::Type::kSessionRateTooLow: {
      const auto ended = sessions_.session_ended(device_index_, event.slot, event.generation);
      if (event.type == device::LoopEvent::Type::kSessionTimedOut) {
        spdlog::warn("device '{}': session {} of node '{}' timed out after {} ms without a command; motors {}", name,
                     ended ? ended->session_id : "?", ended ? app::log_text(ended->node_name) : "?",
                     event.silence_ns / rt::kNsPerMs, to_string(event.behavior));
      } else if (event.type == device::LoopEvent::Type::kSessionRateTooLow) {
        spdlog::warn(
            "device '{}': session {} of node '{}' answered {:.0f} % of the last {} ticks in time, below its "
            "minimum of {:.0f} %: ended, motors {}",
            name, ended ? ended->session_id : "?", ended ? app::log_text(ended->node_name) : "?",
            100.0 * event.success_rate, kSuccessRateWindowTicks, ended ? 100.0 * ended->min_command_success_rate : 0.0,
            to_string(event.behavior));
      } else {
        spdlog::info("device '{}': session in slot {} {}; motors {}", name, event.slot, session_end_text(event.type),
                     to_string(event.behavior));
      }
      break;
    }
    case device::LoopEvent::Type::kSuccessRateLow:
    case device::LoopEvent::Type::kSuccessRateRecovered: {
      const bool low = event.type == device::LoopEvent::Type::kSuccessRateLow;
      // A rate that hovers at the minimum crosses it often: at most one line a second per device.
      rate_log_.log(low ? spdlog::level::warn : spdlog::level::info, name, [&] {
        return fmt::format(
            "device '{}': the closed-loop session in slot {} answers {:.0f} % of its last {} ticks in "
            "time, {} its minimum",
            name, event.slot, 100.0 * event.success_rate, kSuccessRateWindowTicks, low ? "below" : "back at");
      });
      break;
    }
    case device::LoopEvent::Type::kFaultLatched:
      spdlog::error("device '{}': FAULT {} ({}); joints {}; clear with: robotctl call {} recover", name,
                    event.fault.code, event.fault.text.data(), to_string(event.behavior), name);
      break;
    case device::LoopEvent::Type::kEstopApplied:
      if (event.by_estop_input) device_.set_estop_note("engaged by the device's own e-stop input");
      spdlog::warn("device '{}': e-stop applied ({}), joints {}", name, device_.estop_note(),
                   to_string(event.behavior));
      break;
    case device::LoopEvent::Type::kEstopCleared:
      spdlog::info("device '{}': e-stop reset", name);
      break;
    case device::LoopEvent::Type::kBlackBoxFrozen: {
      // A freeze carries the fault that caused it; none means someone asked for a capture.
      const std::string reason = event.fault.code != 0
                                     ? "fault " + std::to_string(event.fault.code) + ": " + event.fault.text.data()
                                     : "requested";
      if (black_box_.capture_if_frozen(reason)) spdlog::info("{}", black_box_.summary());
      break;
    }
  }
}

void StatePublisher::publish_state(const device::LoopState& state) {
  if (!state.state_due || state.state == DeviceState::kConnecting) return;
  // Stamped with the tick's deadline, on the wall clock ROS tools expect.
  const std::int64_t deadline_wall_ns = rt::realtime_now_ns() - (rt::monotonic_now_ns() - state.deadline_ns);
  const Header header{Time::from_ns(deadline_wall_ns), device_.model().name};
  publish_tick_state(state, header);
  publish_joint_state(state, header);
  if (device_.model().has_imu && state.feedback.has_imu) publish_imu(state.feedback.imu, header);
}

// Only while a closed-loop client listens: the same state again, with what it needs to answer.
void StatePublisher::publish_tick_state(const device::LoopState& state, const Header& header) {
  if (writers_.tick_state == nullptr || writers_.tick_state->matched_readers() == 0) return;
  tick_state_.header.stamp = header.stamp;
  tick_state_.tick = state.tick;
  tick_state_.deadline_steady_ns = state.deadline_ns;
  tick_state_.period_ns = state.period_ns;
  tick_state_.state_ready_steady_ns = state.ready_ns;
  tick_state_.state = state.state;
  const std::size_t count = device_.model().joint_count();
  for (std::size_t j = 0; j < count; ++j) {
    tick_state_.position[j] = state.feedback.joints[j].position_rad;
    tick_state_.velocity[j] = state.feedback.joints[j].velocity_rad_s;
    tick_state_.effort[j] = state.feedback.joints[j].effort_nm;
  }
  tick_state_.has_imu = device_.model().has_imu && state.feedback.has_imu;
  if (tick_state_.has_imu) {
    const driver::ImuSample& imu = state.feedback.imu;
    tick_state_.imu_orientation = {imu.orientation_xyzw[0], imu.orientation_xyzw[1], imu.orientation_xyzw[2],
                                   imu.orientation_xyzw[3]};
    tick_state_.imu_angular_velocity = {imu.angular_velocity_rad_s[0], imu.angular_velocity_rad_s[1],
                                        imu.angular_velocity_rad_s[2]};
    tick_state_.imu_linear_acceleration = {imu.linear_acceleration_m_s2[0], imu.linear_acceleration_m_s2[1],
                                           imu.linear_acceleration_m_s2[2]};
  }
  tick_state_.published_steady_ns = rt::monotonic_now_ns();
  (void)writers_.tick_state->write(tick_state_);
}

void StatePublisher::publish_joint_state(const device::LoopState& state, const Header& header) {
  const std::size_t count = device_.model().joint_count();
  joint_state_.header.stamp = header.stamp;
  for (std::size_t j = 0; j < count; ++j) {
    joint_state_.position[j] = state.feedback.joints[j].position_rad;
    joint_state_.velocity[j] = state.feedback.joints[j].velocity_rad_s;
    joint_state_.effort[j] = state.feedback.joints[j].effort_nm;
  }
  if (writers_.joint_states->write(joint_state_)) {
    const std::lock_guard lock(published_mutex_);
    ++joint_states_published_;
    last_published_stamp_ns_ = joint_state_.header.stamp.to_ns();
  }
}

void StatePublisher::publish_imu(const driver::ImuSample& sample, const Header& header) {
  Imu imu;
  imu.header = header;
  imu.orientation = {sample.orientation_xyzw[0], sample.orientation_xyzw[1], sample.orientation_xyzw[2],
                     sample.orientation_xyzw[3]};
  imu.angular_velocity = {sample.angular_velocity_rad_s[0], sample.angular_velocity_rad_s[1],
                          sample.angular_velocity_rad_s[2]};
  imu.linear_acceleration = {sample.linear_acceleration_m_s2[0], sample.linear_acceleration_m_s2[1],
                             sample.linear_acceleration_m_s2[2]};
  const ImuWriters& writers = writers_.imu;
  if (writers.imu != nullptr) (void)writers.imu->write(imu);
  if (writers.yesense_imu == nullptr) return;  // the PI Plus topics are off
  // Five more samples per tick at up to 1 kHz: only written while someone reads them.
  const auto write_if_read = [](const auto* writer, const auto& value) {
    if (writer->matched_readers() > 0) (void)writer->write(value);
  };
  const YesenseImu yesense = yesense_imu(imu);
  write_if_read(writers.yesense_rpy, yesense.rpy_deg);
  write_if_read(writers.yesense_acc, yesense.acc_m_s2);
  write_if_read(writers.yesense_gyro, yesense.gyro_deg_s);
  write_if_read(writers.yesense_quat, yesense.quaternion);
  write_if_read(writers.yesense_imu, imu);
}

void StatePublisher::publish_end_pose(const device::LoopState& state) {
  const int rate_hz = device_.config().end_pose_rate_hz;
  if (rate_hz <= 0 || !device_.model().has_end_pose || !state.feedback.has_end_pose || writers_.end_pose == nullptr) {
    return;
  }
  const std::int64_t now = rt::monotonic_now_ns();
  if (now < next_end_pose_ns_) return;
  next_end_pose_ns_ = now + rt::kNsPerSecond / rate_hz;
  const driver::Pose& pose = state.feedback.end_pose;
  PoseStamped message;
  message.header.stamp = Time::from_ns(rt::realtime_now_ns());
  message.header.frame_id = device_.model().name;
  message.position = {pose.position_m[0], pose.position_m[1], pose.position_m[2]};
  message.orientation = {pose.orientation_xyzw[0], pose.orientation_xyzw[1], pose.orientation_xyzw[2],
                         pose.orientation_xyzw[3]};
  (void)writers_.end_pose->write(message);
}

DeviceStatus StatePublisher::device_status() const {
  const device::LoopState state = latest();
  DeviceStatus status;
  status.header.stamp = Time::from_ns(rt::realtime_now_ns());
  status.header.frame_id = device_.model().name;
  status.device = device_.model().name;
  status.driver = device_.model().driver;
  // Before the loop's first tick the device is still connecting.
  status.state = state.tick == 0 ? DeviceState::kConnecting : state.state;
  status.state_text = state_text(state, device_.estop_note());
  status.fault_code = state.state == DeviceState::kFault ? state.fault.code : 0;
  status.fault_text = state.state == DeviceState::kFault ? state.fault.text.data() : "";
  status.estop_engaged = state.estop;
  {
    const std::lock_guard lock(window_mutex_);
    status.loop = window_.summarize();
  }
  status.loop.rate_hz = device_.model().rate_hz;
  status.loop.realtime = device_.thread_start().realtime;
  status.loop.ticks = state.tick;
  status.loop.overruns = state.overruns;
  status.loop.rt_heap_allocations = state.rt_allocations;
  status.loop.tick_deadline_steady_ns = state.deadline_ns;
  status.loop.period_ns = state.period_ns;
  status.commands = counters_.snapshot(device_.channel().dropped_stale.load(std::memory_order_relaxed));
  {
    const std::lock_guard lock(published_mutex_);
    status.joint_states_published = joint_states_published_;
  }
  for (auto& [key, value] : device_.driver().diagnostics()) status.driver_values.push_back({key, value});
  const std::uint64_t lost = device_.channel().lost_events.load(std::memory_order_relaxed);
  if (lost > 0) status.driver_values.push_back({"robotd.lost_loop_events", std::to_string(lost)});
  return status;
}

void StatePublisher::publish_device_status() { (void)writers_.device_status->write(device_status()); }

device::LoopState StatePublisher::latest() const {
  const std::lock_guard lock(latest_mutex_);
  return latest_;
}

nlohmann::json StatePublisher::loop_timing(bool samples, bool reset) {
  std::vector<device::TickTiming> window;
  {
    const std::lock_guard lock(window_mutex_);
    window = window_.samples();
    if (reset) window_.clear();
  }
  std::vector<std::int64_t> wake;
  std::vector<std::int64_t> execution;
  std::vector<std::int64_t> period;
  std::vector<std::int64_t> round_trip;  // ticks that took an answer only
  for (const auto& timing : window) {
    wake.push_back(timing.wake_latency_ns);
    execution.push_back(timing.execution_ns);
    period.push_back(timing.period_ns);
    if (timing.answer_round_trip_ns >= 0) round_trip.push_back(timing.answer_round_trip_ns);
  }
  const device::LoopState state = latest();
  nlohmann::json out = {{"device", device_.model().name},
                        {"window_ticks", window.size()},
                        {"ticks", state.tick},
                        {"overruns", state.overruns}};
  {
    const std::lock_guard lock(published_mutex_);
    out["joint_states_published"] = joint_states_published_;
    out["last_published_stamp_ns"] = last_published_stamp_ns_;  // header.stamp of the last one counted
  }
  if (samples) {  // before percentiles() reorders them
    out["wake_latency_ns"] = wake;
    out["execution_ns"] = execution;
    out["answer_round_trip_ns"] = round_trip;
  }
  const auto summary = [](std::vector<std::int64_t>& values) {
    const device::Percentiles p = device::percentiles(values);
    const auto us = [](float value) { return std::round(static_cast<double>(value) * 1000.0) / 1000.0; };
    return nlohmann::json{{"p50", us(p.p50)}, {"p99", us(p.p99)}, {"p999", us(p.p999)}, {"max", us(p.max)}};
  };
  out["wake_latency_us"] = summary(wake);
  out["execution_us"] = summary(execution);
  out["period_us"] = summary(period);
  out["answers"] = round_trip.size();
  out["answer_round_trip_us"] = summary(round_trip);
  return out;
}

}  // namespace robotd::dds
