// A RealMan arm behind its controller's TCP JSON port and UDP push (docs/drivers/realman.md).
//
// RT thread: read() copies the newest feedback the link thread published (joints, pose, the
// controller's errors); write() publishes what to stream (the session's joint targets, or
// nothing, or the e-stop). No JSON, no sockets, no locks on the RT thread.
// Link thread (controller_link.hpp): every socket and every JSON text.
// Other threads: connect/recover/disconnect (loop paused) and the device_call ops, which send
// requests through the link and wait for replies, never holding up the RT thread.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

#include "codec/realman_codec.hpp"
#include "driver/arm_fault.hpp"
#include "driver/controller_link.hpp"
#include "driver/realman_params.hpp"
#include "robotd/driver/abort_flag.hpp"
#include "robotd/driver/driver.hpp"

namespace robotd::realman {

class RealmanDriver final : public driver::Driver {
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
  friend class RealmanOps;

  Result<void> connect_locked();
  /// RT: false, with the reason in `fault`, while not connected or the link is lost.
  bool link_up(driver::FaultInfo& fault) noexcept;
  /// Reads the controller's model and firmware and checks the model against the config.
  Result<void> check_software();
  Result<void> start_push();
  Result<void> await_feedback();
  Result<void> clear_errors();
  /// For connect and recover: the configured request timeout, and abort_ ends the wait.
  Result<ControllerLink::Reply> request(const nlohmann::json& message);
  Result<ControllerLink::Reply> request(const nlohmann::json& message, const RequestOptions& options);
  RequestOptions default_options() const;

  RealmanParams params_;
  bool configured_ = false;
  ControllerLink link_;
  std::mutex link_mutex_;    // connect / recover / disconnect; never taken by the RT thread
  std::mutex ops_mutex_;     // one op at a time
  driver::AbortFlag abort_;  // abort_maintenance(): connect and recover stop waiting
  std::string product_version_;
  std::string controller_version_;

  std::atomic<bool> connected_{false};
  std::atomic<bool> session_streaming_{false};  // for the ops: a session owns joints

  // RT thread.
  LinkHealth rt_health_;  // the newest health read()/write() could read
  std::uint64_t last_sequence_ = 0;
  ArmFeedback rt_feedback_;  // the newest read(); write() holds unowned joints where it measured them
  driver::FaultInfo not_connected_fault_;
};

}  // namespace robotd::realman
