// TCP and UDP helpers on loopback: real sockets, no traffic beyond 127.0.0.1.
#include "robotd/transport/ip_socket.hpp"

#include <array>
#include <chrono>
#include <netinet/in.h>
#include <string>
#include <sys/socket.h>
#include <thread>

#include <gtest/gtest.h>

#include "unanswered_port.hpp"

namespace robotd::transport {
namespace {

using namespace std::chrono_literals;

Endpoint any_loopback_port() { return Endpoint{"127.0.0.1", 0}; }

std::string receive(int fd) {
  std::array<char, 256> buffer{};
  if (!wait_readable(fd, 2s)) return "(nothing)";
  const ssize_t n = ::recv(fd, buffer.data(), buffer.size(), 0);
  return n > 0 ? std::string(buffer.data(), static_cast<std::size_t>(n)) : std::string("(closed)");
}

TEST(IpSocket, ConnectsToAListenerAndCarriesBytesBothWays) {
  auto listener = listen_tcp(any_loopback_port());
  ASSERT_TRUE(listener) << listener.error().message;
  const auto port = local_endpoint(listener.value().fd());
  ASSERT_TRUE(port);
  ASSERT_NE(port.value().port, 0);

  auto client = connect_tcp(port.value(), 1s);
  ASSERT_TRUE(client) << client.error().message;
  ASSERT_TRUE(wait_readable(listener.value().fd(), 2s));
  const Socket server(::accept4(listener.value().fd(), nullptr, nullptr, SOCK_CLOEXEC));
  ASSERT_TRUE(server.is_open());

  std::size_t sent = 0;
  EXPECT_EQ(send_some(client.value().fd(), "hello\r\n", sent), SendResult::kSent);
  EXPECT_EQ(sent, 7U);
  EXPECT_EQ(receive(server.fd()), "hello\r\n");
  const auto peer = peer_endpoint(client.value().fd());
  ASSERT_TRUE(peer);
  EXPECT_EQ(peer.value().to_string(), port.value().to_string());
}

TEST(IpSocket, ConnectionRefusedIsNotAvailableAndNamesThePeer) {
  Endpoint closed_port;
  {
    auto listener = listen_tcp(any_loopback_port());
    ASSERT_TRUE(listener);
    closed_port = local_endpoint(listener.value().fd()).value();
  }
  auto client = connect_tcp(closed_port, 1s);
  ASSERT_FALSE(client);
  EXPECT_EQ(client.error().code, ErrorCode::kNotAvailable);
  EXPECT_NE(client.error().message.find(closed_port.to_string()), std::string::npos) << client.error().message;
}

TEST(IpSocket, AnAbortEndsTheWaitForAPeerThatDoesNotAnswer) {
  const testing::UnansweredPort unanswered;
  const Endpoint peer{"127.0.0.1", unanswered.port()};
  const auto timed_out = connect_tcp(peer, 100ms);
  ASSERT_FALSE(timed_out);
  EXPECT_NE(timed_out.error().message.find("no answer within 100 ms"), std::string::npos) << timed_out.error().message;

  driver::AbortFlag abort;
  std::thread aborter([&] {
    std::this_thread::sleep_for(100ms);
    abort.request();
  });
  const auto started = std::chrono::steady_clock::now();
  const auto aborted = connect_tcp(peer, 5s, &abort);
  const auto waited = std::chrono::steady_clock::now() - started;
  aborter.join();
  ASSERT_FALSE(aborted);
  EXPECT_EQ(aborted.error().code, ErrorCode::kRefused);
  EXPECT_EQ(aborted.error().message,
            "aborted: an e-stop or shutdown pre-empted connecting to 127.0.0.1:" + std::to_string(unanswered.port()));
  EXPECT_LT(waited, 1s) << "the 5 s connection attempt ran on after the abort";
}

TEST(IpSocket, AnAddressThatIsNotIpv4IsRefusedWithTheExpectedForm) {
  auto client = connect_tcp(Endpoint{"robot.local", 8080}, 1s);
  ASSERT_FALSE(client);
  EXPECT_EQ(client.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(client.error().message.find("dotted"), std::string::npos) << client.error().message;
}

TEST(IpSocket, SendingToAClosedPeerSaysClosedWithoutSigpipe) {
  auto listener = listen_tcp(any_loopback_port());
  ASSERT_TRUE(listener);
  auto client = connect_tcp(local_endpoint(listener.value().fd()).value(), 1s);
  ASSERT_TRUE(client);
  ASSERT_TRUE(wait_readable(listener.value().fd(), 2s));
  Socket(::accept4(listener.value().fd(), nullptr, nullptr, SOCK_CLOEXEC)).reset();  // accept, then close at once
  const std::string chunk(std::size_t{64} * 1024, 'x');
  SendResult result = SendResult::kSent;
  for (int i = 0; i < 100 && result != SendResult::kClosed; ++i) {
    std::size_t sent = 0;
    result = send_some(client.value().fd(), chunk, sent);
  }
  EXPECT_EQ(result, SendResult::kClosed);
}

TEST(IpSocket, UdpDatagramsArriveAtTheBoundPort) {
  auto receiver = bind_udp(any_loopback_port());
  ASSERT_TRUE(receiver) << receiver.error().message;
  auto sender = bind_udp(any_loopback_port());
  ASSERT_TRUE(sender);
  const Endpoint target = local_endpoint(receiver.value().fd()).value();
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(target.port);
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const std::string datagram = "{\"state\":\"realtime_arm_joint_state\"}\r\n";
  ASSERT_EQ(::sendto(sender.value().fd(), datagram.data(), datagram.size(), 0, reinterpret_cast<sockaddr*>(&address),
                     sizeof(address)),  // NOLINT: sockets API
            static_cast<ssize_t>(datagram.size()));
  EXPECT_EQ(receive(receiver.value().fd()), datagram);
}

TEST(IpSocket, BindingAPortInUseSaysWhichAndWhy) {
  auto first = bind_udp(any_loopback_port());
  ASSERT_TRUE(first);
  const Endpoint taken = local_endpoint(first.value().fd()).value();
  auto second = bind_udp(taken);
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().code, ErrorCode::kNotAvailable);
  EXPECT_NE(second.error().message.find(taken.to_string()), std::string::npos) << second.error().message;
}

}  // namespace
}  // namespace robotd::transport
