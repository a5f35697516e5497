// robotd as a whole: builds every part from the config, starts them in dependency order and
// stops them in reverse, bringing each device to its safe stop before its driver disconnects.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "dds/command_intake.hpp"
#include "dds/dds_log_sink.hpp"
#include "dds/service_host.hpp"
#include "dds/session_status_publisher.hpp"
#include "dds/state_publisher.hpp"
#include "device/black_box.hpp"
#include "device/device.hpp"
#include "joystick/joystick_source.hpp"
#include "rt/realtime_environment.hpp"
#include "service/device_services.hpp"
#include "service/reconnector.hpp"
#include "service/session_service.hpp"
#include "wire/participant.hpp"

namespace robotd::app {

class Daemon {
 public:
  explicit Daemon(config::Config config);
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;
  ~Daemon();

  /// Starts everything. Fails if a required device cannot start, or no device can.
  Result<void> start();
  /// Safe stop of every device, then everything else, in reverse order.
  void stop();

  /// "" while every device loop ticks; otherwise which one is stuck (for the watchdog).
  std::string loop_problem();
  std::string summary() const;

 private:
  Result<void> start_devices();
  Result<void> start_dds();
  Result<void> start_imu_writers();
  Result<void> start_joystick();

  config::Config config_;
  std::optional<rt::CpuLatencyRequest> cpu_latency_;
  bool memory_locked_ = false;  // mlockall succeeded: loaded objects are locked before each loop starts
  std::vector<std::unique_ptr<device::Device>> devices_;
  std::vector<device::Device*> device_ptrs_;
  std::vector<std::unique_ptr<device::BlackBox>> black_boxes_;
  dds::SurfaceCounterSet surface_counters_;
  std::unique_ptr<dds::DdsLogSink> dds_log_;  // declared before the participant, so it outlives it
  std::unique_ptr<wire::Participant> participant_;
  std::unique_ptr<wire::TopicWriter<JointState>> joint_states_;
  std::unique_ptr<wire::TopicWriter<Imu>> imu_;
  std::unique_ptr<wire::TopicWriter<DeviceStatus>> device_status_;
  std::unique_ptr<wire::TopicWriter<PoseStamped>> end_pose_;
  std::vector<std::unique_ptr<wire::TopicWriter<TickState>>> tick_states_;  // per device
  // The PI Plus IMU node's topics, when a device has an IMU (and daemon.yesense_imu_topics).
  std::unique_ptr<wire::TopicWriter<Vector3>> yesense_rpy_;
  std::unique_ptr<wire::TopicWriter<Vector3>> yesense_acc_;
  std::unique_ptr<wire::TopicWriter<Vector3>> yesense_gyro_;
  std::unique_ptr<wire::TopicWriter<Quaternion>> yesense_quat_;
  std::unique_ptr<wire::TopicWriter<Imu>> yesense_imu_;
  std::unique_ptr<wire::TopicWriter<Joy>> joy_;
  std::unique_ptr<joystick::JoystickSource> joystick_;
  std::unique_ptr<dds::SessionStatusPublisher> session_status_;
  std::unique_ptr<service::SessionService> sessions_;
  std::unique_ptr<service::DeviceServices> device_services_;
  std::unique_ptr<dds::CommandIntake> intake_;
  std::unique_ptr<dds::ServiceHost> services_;
  std::unique_ptr<service::Reconnector> reconnector_;
  std::vector<std::unique_ptr<dds::StatePublisher>> publishers_;
  std::vector<std::uint64_t> watched_ticks_;
  bool stopped_ = false;
};

}  // namespace robotd::app
