// Per device, off the RT thread: woken by the loop right after each tick, publishes that tick's
// state on /joint_states (with /imu and the PI Plus /yesense_imu/* topics) and /<device>/tick_state
// (every state_every_ticks-th tick), /device_status at the status rate, folds the loop's tick
// timings into the statistics window, and acts on what the loop reports (sessions it ended,
// faults, black box). It is the single reader of the loop's state mailbox and event rings.
#pragma once

#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

#include "app/throttled_log.hpp"
#include "config/config.hpp"
#include "device/black_box.hpp"
#include "device/device.hpp"
#include "device/loop_statistics.hpp"
#include "robotd/driver/named_thread.hpp"
#include "service/command_counters.hpp"
#include "service/device_observer.hpp"
#include "service/session_service.hpp"
#include "wire/topic_io.hpp"

namespace robotd::dds {

/// /imu and the PI Plus IMU node's topics; a null writer is not published.
struct ImuWriters {
  const wire::TopicWriter<Imu>* imu = nullptr;
  const wire::TopicWriter<Vector3>* yesense_rpy = nullptr;   // degrees
  const wire::TopicWriter<Vector3>* yesense_acc = nullptr;   // m/s²
  const wire::TopicWriter<Vector3>* yesense_gyro = nullptr;  // deg/s
  const wire::TopicWriter<Quaternion>* yesense_quat = nullptr;
  const wire::TopicWriter<Imu>* yesense_imu = nullptr;
};

struct StateWriters {
  const wire::TopicWriter<JointState>* joint_states = nullptr;
  ImuWriters imu;
  const wire::TopicWriter<DeviceStatus>* device_status = nullptr;
  const wire::TopicWriter<PoseStamped>* end_pose = nullptr;
  const wire::TopicWriter<TickState>* tick_state = nullptr;  // the device's own topic
};

class StatePublisher final : public service::DeviceObserver {
 public:
  StatePublisher(device::Device& device, std::size_t device_index, StateWriters writers,
                 service::SessionService& sessions, const service::CommandCounterSet& counters,
                 device::BlackBox& black_box, const config::DaemonConfig& daemon);
  StatePublisher(const StatePublisher&) = delete;
  StatePublisher& operator=(const StatePublisher&) = delete;
  ~StatePublisher() override;

  void start();
  /// After the device has stopped: handles what the loop said last and publishes the final
  /// (STOPPED) status, then ends the thread.
  void finish();

  device::LoopState latest() const override;
  nlohmann::json loop_timing(bool samples, bool reset) override;

 private:
  DeviceStatus device_status() const;
  void run();
  void drain_loop(bool publish_states);
  void handle(const device::LoopEvent& event);
  void publish_state(const device::LoopState& state);
  void publish_joint_state(const device::LoopState& state, const Header& header);
  void publish_tick_state(const device::LoopState& state, const Header& header);
  void publish_imu(const driver::ImuSample& sample, const Header& header);
  void publish_end_pose(const device::LoopState& state);
  void publish_device_status();

  device::Device& device_;
  std::size_t device_index_;
  StateWriters writers_;
  service::SessionService& sessions_;
  const service::CommandCounterSet& counters_;
  device::BlackBox& black_box_;
  const config::DaemonConfig& daemon_;

  mutable std::mutex window_mutex_;  // the window is fed here and read by loop_timing() on a service thread
  device::LoopStatisticsWindow window_;
  // How many /joint_states samples went out, and the stamp of the last one, updated together so
  // a reader can tell exactly which samples the count covers.
  mutable std::mutex published_mutex_;
  std::uint64_t joint_states_published_ = 0;
  std::int64_t last_published_stamp_ns_ = 0;
  JointState joint_state_;
  TickState tick_state_;
  std::int64_t next_end_pose_ns_ = 0;
  mutable std::mutex latest_mutex_;
  device::LoopState latest_{};
  app::ThrottledLog rate_log_;
  std::atomic<bool> stopping_{false};
  driver::NamedThread thread_;
};

}  // namespace robotd::dds
