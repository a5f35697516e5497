#include "app/daemon.hpp"

#include <spdlog/spdlog.h>

#include "plugin/plugin_loader.hpp"
#include "rt/memory_lock.hpp"
#include "rt/realtime_environment.hpp"
#include "wire/qos.hpp"
#include "wire/topics.hpp"

namespace robotd::app {
namespace {

// Deep enough that a subscriber that misses a few 1 kHz samples can still catch up.
constexpr int kStateHistoryDepth = 10;
// A closed-loop client answers the newest state only: an older one is never worth delivering.
constexpr int kTickStateHistoryDepth = 1;

template <class T>
Result<void> create_writer(const wire::Participant& participant, std::string_view topic, const dds_qos_t* qos,
                           std::unique_ptr<wire::TopicWriter<T>>& out) {
  auto writer = wire::TopicWriter<T>::create(participant, topic, qos);
  if (!writer) return writer.error();
  out = std::make_unique<wire::TopicWriter<T>>(std::move(writer.value()));
  return {};
}

}  // namespace

Daemon::Daemon(config::Config config) : config_(std::move(config)) {}

Daemon::~Daemon() { stop(); }

Result<void> Daemon::start() {
  const rt::EnvironmentReport environment = rt::inspect_environment();
  spdlog::info("real-time check: {}", rt::describe(environment));
  for (const auto& warning : environment.warnings) spdlog::warn("real-time check: {}", warning);

  const bool wants_realtime = std::any_of(config_.devices.begin(), config_.devices.end(), [](const auto& device) {
    return device.realtime != rt::RealtimePolicy::kOff;
  });
  if (wants_realtime) {
    if (const std::string failure = rt::lock_memory(); !failure.empty()) {
      const bool required = std::any_of(config_.devices.begin(), config_.devices.end(), [](const auto& device) {
        return device.realtime == rt::RealtimePolicy::kRequire;
      });
      if (required) return make_error(ErrorCode::kRefused, "a device has realtime: require, but " + failure);
      spdlog::warn("{}", failure);
    } else {
      memory_locked_ = true;
    }
  }
  if (config_.dds.receive_thread_priority > 0 && !environment.can_use_fifo) {
    spdlog::warn(
        "DDS receive thread: SCHED_FIFO not permitted, so it runs SCHED_OTHER: busy processes on this "
        "machine can keep it from draining its sockets, and commands are then lost (docs/reliability.md)");
    config_.dds.receive_thread_priority = 0;
  }
  if (config_.daemon.loop_io_priority > 0 && !environment.can_use_fifo) {
    spdlog::warn(
        "state publishers and command intake: SCHED_FIFO not permitted, so they run SCHED_OTHER: busy processes "
        "on this machine delay each tick's state and the commands that answer it (docs/performance.md)");
    config_.daemon.loop_io_priority = 0;
  }
  if (config_.daemon.cpu_dma_latency_us >= 0) {
    auto request = rt::CpuLatencyRequest::hold(config_.daemon.cpu_dma_latency_us);
    if (request) {
      cpu_latency_.emplace(std::move(request.value()));
      spdlog::info("real-time check: holding a {} µs CPU wake-up latency request (/dev/cpu_dma_latency)",
                   config_.daemon.cpu_dma_latency_us);
    } else {
      spdlog::warn("real-time check: {}", request.error().message);
    }
  }
  if (auto devices = start_devices(); !devices) return devices;
  return start_dds();
}

Result<void> Daemon::start_devices() {
  const auto search_path = plugin::plugin_search_path(config_.daemon.plugin_dirs);
  for (const auto& device_config : config_.devices) {
    const auto fail = [&](const Error& error) -> Result<void> {
      if (device_config.required) return make_error(error.code, error.message + " (the device is required)");
      spdlog::error("{} — continuing without device '{}' (required: false)", error.message, device_config.name);
      return {};
    };
    auto loaded = plugin::load_driver(device_config.driver, search_path);
    if (!loaded) {
      if (auto result = fail(make_error(loaded.error().code, device_config.path + ": " + loaded.error().message));
          !result) {
        return result;
      }
      continue;
    }
    auto device = std::make_unique<device::Device>(device_config, std::move(loaded.value()));
    if (auto configured = device->configure(); !configured) {
      if (auto result = fail(configured.error()); !result) return result;
      continue;
    }
    if (memory_locked_) {
      // The driver plugin was just loaded: its code is locked before its loop first runs it.
      if (const std::string failure = rt::lock_loaded_objects(); !failure.empty()) spdlog::warn("{}", failure);
    }
    if (auto started = device->start(); !started) {
      if (auto result = fail(started.error()); !result) return result;
      continue;
    }
    const auto& model = device->model();
    spdlog::info("device '{}': driver {} {} ({}), {} joints, {} Hz loop; {}", model.name, model.driver,
                 model.driver_version, model.model, model.joint_count(), model.rate_hz, device->thread_start().report);
    if (!device->thread_start().realtime && device_config.realtime != rt::RealtimePolicy::kOff) {
      spdlog::warn("device '{}': loop is NOT real-time: {}", model.name, device->thread_start().report);
    }
    devices_.push_back(std::move(device));
  }
  if (devices_.empty()) return make_error(ErrorCode::kRefused, "no device could be started");
  for (auto& device : devices_) {
    device_ptrs_.push_back(device.get());
    black_boxes_.push_back(std::make_unique<device::BlackBox>(device->channel(), device->model()));
  }
  watched_ticks_.assign(devices_.size(), 0);
  return {};
}

Result<void> Daemon::start_dds() {
  dds_log_ = std::make_unique<dds::DdsLogSink>(surface_counters_);
  auto participant = wire::Participant::create(config_.dds);
  if (!participant) return participant.error();
  participant_ = std::make_unique<wire::Participant>(std::move(participant.value()));

  const auto state_qos = wire::reliable_qos(kStateHistoryDepth);
  for (const auto& created : {create_writer(*participant_, wire::kJointStatesTopic, state_qos.get(), joint_states_),
                              create_writer(*participant_, wire::kImuTopic, state_qos.get(), imu_),
                              create_writer(*participant_, wire::kDeviceStatusTopic, state_qos.get(), device_status_),
                              create_writer(*participant_, wire::kEndPoseTopic, state_qos.get(), end_pose_)}) {
    if (!created) return created;
  }
  if (auto imu_writers = start_imu_writers(); !imu_writers) return imu_writers;
  const auto tick_state_qos = wire::reliable_qos(kTickStateHistoryDepth);
  tick_states_.resize(devices_.size());
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    const std::string topic = wire::tick_state_topic(devices_[i]->model().name);
    if (auto created = create_writer(*participant_, topic, tick_state_qos.get(), tick_states_[i]); !created) {
      return created;
    }
  }

  auto session_status = dds::SessionStatusPublisher::create(
      *participant_, std::chrono::milliseconds(config_.daemon.session_status_period_ms));
  if (!session_status) return session_status.error();
  session_status_ = std::move(session_status.value());

  sessions_ = std::make_unique<service::SessionService>(
      device_ptrs_,
      session::SessionLimits{config_.daemon.min_session_timeout_ms, config_.daemon.max_session_timeout_ms},
      [this] { session_status_->changed(); });
  intake_ = std::make_unique<dds::CommandIntake>(*participant_, device_ptrs_, *sessions_, surface_counters_);

  dds::StateWriters writers{.joint_states = joint_states_.get(),
                            .imu = {.imu = imu_.get(),
                                    .yesense_rpy = yesense_rpy_.get(),
                                    .yesense_acc = yesense_acc_.get(),
                                    .yesense_gyro = yesense_gyro_.get(),
                                    .yesense_quat = yesense_quat_.get(),
                                    .yesense_imu = yesense_imu_.get()},
                            .device_status = device_status_.get(),
                            .end_pose = end_pose_.get()};
  std::vector<service::DeviceObserver*> observers;
  std::vector<device::BlackBox*> boxes;
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    writers.tick_state = tick_states_[i].get();
    publishers_.push_back(std::make_unique<dds::StatePublisher>(
        *devices_[i], i, writers, *sessions_, intake_->counters(i), *black_boxes_[i], config_.daemon));
    observers.push_back(publishers_.back().get());
    boxes.push_back(black_boxes_[i].get());
  }
  sessions_->read_answers_from(observers);
  device_services_ = std::make_unique<service::DeviceServices>(device_ptrs_, boxes, observers, *sessions_);
  reconnector_ = std::make_unique<service::Reconnector>(device_ptrs_, observers);
  auto services = dds::ServiceHost::create(*participant_, *sessions_, *device_services_, surface_counters_);
  if (!services) return services.error();
  services_ = std::move(services.value());

  for (auto& publisher : publishers_) publisher->start();
  reconnector_->start();
  session_status_->start(*sessions_, surface_counters_);
  if (auto started = intake_->start(config_.daemon.loop_io_priority); !started) return started;
  services_->start();
  if (auto joystick = start_joystick(); !joystick) return joystick;
  spdlog::info(
      "DDS: domain {}, {}", config_.dds.domain_id,
      config_.dds.cyclonedds_xml.empty()
          ? "interface " +
                (config_.dds.network_interface.empty() ? std::string("(auto)") : config_.dds.network_interface) +
                (config_.dds.multicast ? ", multicast" : ", no multicast") +
                (config_.dds.receive_thread_priority > 0
                     ? ", receive thread SCHED_FIFO " + std::to_string(config_.dds.receive_thread_priority)
                     : std::string(", receive threads SCHED_OTHER"))
          : std::string("custom Cyclone DDS XML"));
  return {};
}

Result<void> Daemon::start_imu_writers() {
  const bool any_imu =
      std::any_of(devices_.begin(), devices_.end(), [](const auto& device) { return device->model().has_imu; });
  if (!any_imu || !config_.daemon.yesense_imu_topics) return {};
  const auto qos = wire::reliable_qos(kStateHistoryDepth);  // PI Plus clients subscribe reliable
  for (const auto& created : {create_writer(*participant_, wire::kYesenseRpyTopic, qos.get(), yesense_rpy_),
                              create_writer(*participant_, wire::kYesenseAccTopic, qos.get(), yesense_acc_),
                              create_writer(*participant_, wire::kYesenseGyroTopic, qos.get(), yesense_gyro_),
                              create_writer(*participant_, wire::kYesenseQuatTopic, qos.get(), yesense_quat_),
                              create_writer(*participant_, wire::kYesenseImuTopic, qos.get(), yesense_imu_)}) {
    if (!created) return created;
  }
  return {};
}

Result<void> Daemon::start_joystick() {
  if (!config_.joystick) return {};
  const auto qos = wire::reliable_qos(kStateHistoryDepth);
  if (auto created = create_writer(*participant_, wire::data_topic(config_.joystick->topic), qos.get(), joy_);
      !created) {
    return created;
  }
  joystick_ = std::make_unique<joystick::JoystickSource>(
      *config_.joystick, [writer = joy_.get()](const Joy& joy) { (void)writer->write(joy); });
  joystick_->start();
  return {};
}

void Daemon::stop() {
  if (stopped_) return;
  stopped_ = true;
  if (joystick_) joystick_->stop();  // its last sample is neutral
  if (services_) services_->stop();
  if (intake_) intake_->stop();
  if (reconnector_) reconnector_->stop();
  for (auto& device : devices_) device->request_stop();  // all devices stop in parallel
  for (auto& device : devices_) device->stop();
  for (auto& publisher : publishers_) publisher->finish();
  if (session_status_) session_status_->stop();
  reconnector_.reset();
  publishers_.clear();
  services_.reset();
  intake_.reset();
  device_services_.reset();
  sessions_.reset();
  session_status_.reset();
  joint_states_.reset();
  imu_.reset();
  device_status_.reset();
  end_pose_.reset();
  tick_states_.clear();
  joystick_.reset();
  joy_.reset();
  yesense_rpy_.reset();
  yesense_acc_.reset();
  yesense_gyro_.reset();
  yesense_quat_.reset();
  yesense_imu_.reset();
  participant_.reset();
  dds_log_.reset();
  spdlog::info("robotd stopped: every device brought to its safe stop and disconnected");
}

std::string Daemon::loop_problem() {
  std::string problem;
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    const std::uint64_t ticks = devices_[i]->channel().ticks.load(std::memory_order_acquire);
    if (ticks == watched_ticks_[i]) problem += "loop of '" + devices_[i]->model().name + "' is not ticking; ";
    watched_ticks_[i] = ticks;
  }
  return problem;
}

std::string Daemon::summary() const {
  std::string text = "serving";
  for (const auto& device : devices_) {
    text += " " + device->model().name + " (" + device->model().driver + ", " +
            std::to_string(device->model().joint_count()) + " joints)";
  }
  return text + " on DDS domain " + std::to_string(config_.dds.domain_id);
}

}  // namespace robotd::app
