// A robotd-hightorque-sim process for tests: HighTorque motors on CAN-FD stand-in buses (which a
// test or the driver joins with transport::make_can_transport) and on USB-CDC board ports (ptys,
// opened with transport::SerialPort), with a control channel; ready when it printed "ready".
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim_process.hpp"

namespace robotd::testing {

class HighTorqueSimProcess : public SimProcess {
 public:
  /// One --bus / --board option: a fresh path under /tmp is made for it.
  struct Link {
    enum class Kind { kStandIn, kBoard };
    Kind kind = Kind::kStandIn;
    std::string ids;  // "1-6", "1,2,5", "1-4,7"
  };
  static Link standin(std::string ids) { return Link{.kind = Link::Kind::kStandIn, .ids = std::move(ids)}; }
  static Link board(std::string ids) { return Link{.kind = Link::Kind::kBoard, .ids = std::move(ids)}; }

  /// Starts the simulator with `links` (at least one; the control channel's "bus" index is the
  /// position here) and `extra_args` (e.g. {"--quiet", "--torque-max", "10"}); waits up to 5 s
  /// for it to be ready; throws std::runtime_error if it is not.
  explicit HighTorqueSimProcess(const std::vector<Link>& links, std::vector<std::string> extra_args = {});
  /// Kills it and removes every bus path.
  ~HighTorqueSimProcess() override;
  HighTorqueSimProcess(const HighTorqueSimProcess&) = delete;
  HighTorqueSimProcess& operator=(const HighTorqueSimProcess&) = delete;

  /// The stand-in socket path or the pty symlink of bus `index`.
  const std::string& bus_path(std::size_t index) const { return paths_.at(index); }
  std::size_t bus_count() const { return paths_.size(); }

  /// {"op": "state"}'s reply; throws std::runtime_error unless it is {"ok": true}.
  nlohmann::json state() const;
  /// One motor's entry of state() (throws if there is none).
  nlohmann::json motor_state(std::size_t bus, int motor) const;

  /// The robotd-hightorque-sim executable under test.
  static std::string executable();

 private:
  struct Arguments {
    std::string first_option;
    std::string first_spec;
    std::vector<std::string> rest;
    std::vector<std::string> paths;
  };
  static Arguments arguments(const std::vector<Link>& links, std::vector<std::string> extra_args);
  explicit HighTorqueSimProcess(Arguments arguments);

  std::vector<std::string> paths_;
};

}  // namespace robotd::testing
