// A UFACTORY xArm behind its control box's command port and report port (docs/drivers/xarm.md).
//
// RT thread: read() copies the newest feedback the link thread published (joints, torques, TCP
// pose, the controller's state and codes); write() publishes what to stream (the session's joint
// targets, or nothing, or the e-stop). No frames, no sockets, no locks on the RT thread.
// Link thread (controller_link.hpp): every socket and every frame; servo mode and servo_j.
// Other threads: connect/recover/disconnect (loop paused) and the device_call ops, which send
// requests through the link and wait for replies, never holding up the RT thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

#include "codec/xarm_codec.hpp"
#include "driver/controller_link.hpp"
#include "driver/xarm_params.hpp"
#include "robotd/driver/abort_flag.hpp"
#include "robotd/driver/driver.hpp"

namespace robotd::xarm {

class XarmDriver final : public driver::Driver {
 public:
  Result<void> configure(const nlohmann::json& params) override;
  driver::DeviceDescription describe() const override;

  Result<void> connect() override;
  void disconnect() noexcept override;
  Result<void> recover() override;
  Result<void> reset_zero(std::span<const int> joints) override;
  void abort_maintenance() noexcept override { abort_.request(); }

  driver::IoResult read(driver::Feedback& out, driver::FaultInfo& fault) noexcept override;
  driver::IoResult write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept override;

  Result<nlohmann::json> call(const std::string& op, const nlohmann::json& args) override;
  driver::Diagnostics diagnostics() const override;

 private:
  friend class XarmOps;

  Result<void> connect_locked();
  Result<void> clear_errors_locked();
  /// RT: false, with the reason in `fault`, while not connected or the link is lost.
  bool link_up(driver::FaultInfo& fault) noexcept;
  /// Reads get_version and checks the arm against params.model.
  Result<void> check_version();
  Result<void> await_report();
  /// Sends `requests` one after another; the first that fails or is refused ends it.
  Result<void> run_steps(std::initializer_list<Request> requests);
  /// With the configured request timeout; `abort` for the waits of maintenance.
  Result<Reply> request(const Request& request, const driver::AbortFlag* abort = nullptr);

  XarmParams params_;
  bool configured_ = false;
  ControllerLink link_;
  std::mutex link_mutex_;    // connect / recover / disconnect; never taken by the RT thread
  std::mutex ops_mutex_;     // one op at a time
  driver::AbortFlag abort_;  // abort_maintenance(): connect and recover stop waiting
  Version version_;

  std::atomic<bool> connected_{false};
  std::atomic<bool> session_streaming_{false};  // for the ops: a session owns joints

  // RT thread.
  LinkHealth rt_health_;  // the newest health read()/write() could read
  std::uint64_t last_sequence_ = 0;
  ArmFeedback rt_feedback_;  // the newest read(); write() holds unowned joints where it measured them
  driver::FaultInfo not_connected_fault_;
};

}  // namespace robotd::xarm
