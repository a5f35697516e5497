#include "hightorque_sim_process.hpp"

#include <stdexcept>
#include <unistd.h>

#ifndef ROBOTD_HIGHTORQUE_SIM
#error "ROBOTD_HIGHTORQUE_SIM must point at the robotd-hightorque-sim executable"
#endif

namespace robotd::testing {

std::string HighTorqueSimProcess::executable() { return ROBOTD_HIGHTORQUE_SIM; }

HighTorqueSimProcess::Arguments HighTorqueSimProcess::arguments(const std::vector<Link>& links,
                                                                std::vector<std::string> extra_args) {
  if (links.empty()) throw std::invalid_argument("HighTorqueSimProcess needs at least one bus or board port");
  Arguments out;
  for (std::size_t i = 0; i < links.size(); ++i) {
    const bool board = links[i].kind == Link::Kind::kBoard;
    const std::string path = board ? unique_path("hightorque-tty", "") : unique_path("hightorque-bus");
    out.paths.push_back(path);
    const std::string option = board ? "--board" : "--bus";
    const std::string spec = path + ":" + links[i].ids;
    if (i == 0) {
      out.first_option = option;
      out.first_spec = spec;
    } else {
      out.rest.push_back(option);
      out.rest.push_back(spec);
    }
  }
  out.rest.insert(out.rest.end(), extra_args.begin(), extra_args.end());
  return out;
}

HighTorqueSimProcess::HighTorqueSimProcess(const std::vector<Link>& links, std::vector<std::string> extra_args)
    : HighTorqueSimProcess(arguments(links, std::move(extra_args))) {}

// SimProcess runs `<first option> <first spec> --control <path> <rest…>`: the first bus is its
// "link", the others ride along with the extra arguments, in order.
HighTorqueSimProcess::HighTorqueSimProcess(Arguments arguments)
    : SimProcess(executable(), "hightorque", arguments.first_option, arguments.first_spec, std::move(arguments.rest)),
      paths_(std::move(arguments.paths)) {}

HighTorqueSimProcess::~HighTorqueSimProcess() {
  kill_hard();
  for (const std::string& path : paths_) unlink(path.c_str());
}

nlohmann::json HighTorqueSimProcess::state() const {
  nlohmann::json reply = control({{"op", "state"}});
  if (!reply.value("ok", false)) throw std::runtime_error("robotd-hightorque-sim state failed: " + reply.dump());
  return reply;
}

nlohmann::json HighTorqueSimProcess::motor_state(std::size_t bus, int motor) const {
  const nlohmann::json reply = state();
  for (const nlohmann::json& entry : reply.at("buses").at(bus).at("motors")) {
    if (entry.at("id").get<int>() == motor) return entry;
  }
  throw std::runtime_error("robotd-hightorque-sim has no motor " + std::to_string(motor) + " on bus " +
                           std::to_string(bus));
}

}  // namespace robotd::testing
