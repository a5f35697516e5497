// The main controller's side of the protocol: every frame the host may send, applied to the arm
// model, and the replies the real arm gives (spec §7). Frames of the arm's own kind (feedback,
// replies, a master arm's control stream seen from the other side) and unknown ids are ignored.
#pragma once

#include <string>
#include <vector>

#include "arm_model.hpp"
#include "codec/piper_frames.hpp"

namespace robotd::piper::sim {

class Controller {
 public:
  /// `codec` is the simulator's: a restart may change its id offsets.
  Controller(ArmModel& arm, const CodecOptions& codec, std::string software_version);

  /// Applies one frame from the bus; appends what the arm answers (0x473, 0x47C, 0x476, 0x478,
  /// 0x47B, 0x47E, the 0x4AF burst) to `replies`.
  void handle(const CanMessage& message, std::vector<CanMessage>& replies);

  const CodecOptions& codec() const { return codec_; }
  const std::string& software_version() const { return software_version_; }

 private:
  void answer_joint_limit_query(const JointLimitQuery& query, std::vector<CanMessage>& replies) const;
  void answer_param_enquiry(const ParamEnquiry& enquiry, std::vector<CanMessage>& replies);
  void ack(std::uint8_t command, bool zero_set, std::vector<CanMessage>& replies) const;

  ArmModel& arm_;
  const CodecOptions& codec_;
  std::string software_version_;
};

}  // namespace robotd::piper::sim
