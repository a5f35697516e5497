#include "realman_sim_process.hpp"

#include <stdexcept>

#include "robotd/transport/ip_socket.hpp"

#ifndef ROBOTD_REALMAN_SIM
#error "ROBOTD_REALMAN_SIM must point at the robotd-realman-sim executable"
#endif

namespace robotd::testing {

std::string RealmanSimProcess::executable() { return ROBOTD_REALMAN_SIM; }

std::uint16_t RealmanSimProcess::free_port() {
  auto listener = transport::listen_tcp(transport::Endpoint{"127.0.0.1", 0});
  if (!listener) throw std::runtime_error("no free TCP port on 127.0.0.1: " + listener.error().message);
  auto local = transport::local_endpoint(listener.value().fd());
  if (!local) throw std::runtime_error("cannot read the port bound on 127.0.0.1: " + local.error().message);
  return local.value().port;
}

RealmanSimProcess::RealmanSimProcess(std::vector<std::string> extra_args, std::uint16_t port)
    : SimProcess(executable(), "realman", "--port", std::to_string(port == 0 ? free_port() : port),
                 std::move(extra_args)) {}

std::uint16_t RealmanSimProcess::port() const { return static_cast<std::uint16_t>(std::stoul(link_path())); }

}  // namespace robotd::testing
