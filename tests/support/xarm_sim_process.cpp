#include "xarm_sim_process.hpp"

#include <stdexcept>

#include "robotd/transport/ip_socket.hpp"

#ifndef ROBOTD_XARM_SIM
#error "ROBOTD_XARM_SIM must point at the robotd-xarm-sim executable"
#endif

namespace robotd::testing {
namespace {

std::vector<std::string> with_report_port(std::vector<std::string> args, std::uint16_t report_port) {
  args.insert(args.begin(), {"--report-port", std::to_string(report_port)});
  return args;
}

}  // namespace

std::string XarmSimProcess::executable() { return ROBOTD_XARM_SIM; }

std::uint16_t XarmSimProcess::free_port() {
  auto listener = transport::listen_tcp(transport::Endpoint{"127.0.0.1", 0});
  if (!listener) throw std::runtime_error("no free TCP port on 127.0.0.1: " + listener.error().message);
  auto local = transport::local_endpoint(listener.value().fd());
  if (!local) throw std::runtime_error("cannot read the port bound on 127.0.0.1: " + local.error().message);
  return local.value().port;
}

XarmSimProcess::Ports XarmSimProcess::choose(std::uint16_t port, std::uint16_t report_port) {
  Ports ports{.command = port, .report = report_port};
  while (ports.command == 0 || ports.command == ports.report) ports.command = free_port();
  while (ports.report == 0 || ports.report == ports.command) ports.report = free_port();
  return ports;
}

XarmSimProcess::XarmSimProcess(std::vector<std::string> extra_args, std::uint16_t port, std::uint16_t report_port)
    : XarmSimProcess(std::move(extra_args), choose(port, report_port)) {}

XarmSimProcess::XarmSimProcess(std::vector<std::string> extra_args, Ports ports)
    : SimProcess(executable(), "xarm", "--port", std::to_string(ports.command),
                 with_report_port(std::move(extra_args), ports.report)),
      report_port_(ports.report) {}

std::uint16_t XarmSimProcess::port() const { return static_cast<std::uint16_t>(std::stoul(link_path())); }

}  // namespace robotd::testing
