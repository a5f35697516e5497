// ServiceServer / ServiceClient over real DDS on loopback, in one process: a call gets its own
// reply, never another client's or an earlier call's, and a missing or silent server costs the
// caller no more than its timeout.
#include "wire/service.hpp"

#include <chrono>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "robotd/messages.hpp"
#include "wire/participant.hpp"
#include "wire_test_support.hpp"

namespace robotd::wire {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
using Server = ServiceServer<RequestControlRequest, RequestControlResponse>;
using Client = ServiceClient<RequestControlRequest, RequestControlResponse>;

constexpr std::string_view kService = "request_control";
// How much later than its timeout a failing call may return on a loaded machine.
constexpr auto kLateMargin = 250ms;

RequestControlRequest request_from(const std::string& node_name) {
  RequestControlRequest request;
  request.node_name = node_name;
  request.motor_ids = {1, 2};
  return request;
}

RequestControlResponse grant(const RequestControlRequest& request) {
  RequestControlResponse response;
  response.success = true;
  response.message = "granted to " + request.node_name;
  response.uuid = "uuid-of-" + request.node_name;
  response.motor_ids = request.motor_ids;
  response.applied_behavior = Behavior::kDamping;
  return response;
}

/// Answers every request on its own thread, the way the daemon's DDS side does.
class AnsweringServer {
 public:
  AnsweringServer(Server& server, std::function<RequestControlResponse(const RequestControlRequest&)> answer)
      : thread_([&server, answer = std::move(answer)](const std::stop_token& stop) {
          while (!stop.stop_requested()) {
            server.take_requests([&](const RequestId& id, RequestControlRequest&& request) {
              EXPECT_TRUE(server.reply(id, answer(request)));
            });
            std::this_thread::sleep_for(1ms);
          }
        }) {}

 private:
  std::jthread thread_;
};

std::unique_ptr<Client> make_client(const Participant& participant) {
  auto client = Client::create(participant, kService);
  EXPECT_TRUE(client) << client.error().message;
  return client ? std::move(client.value()) : nullptr;
}

TEST(Service, CallGetsTheServersReply) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  auto server = Server::create(participant.value(), kService);
  ASSERT_TRUE(server) << server.error().message;
  const AnsweringServer answering(*server.value(), grant);
  auto client = make_client(participant.value());
  ASSERT_NE(client, nullptr);

  const auto reply = client->call(request_from("alpha"), 2s);
  ASSERT_TRUE(reply) << reply.error().message;
  EXPECT_TRUE(reply.value().success);
  EXPECT_EQ(reply.value().message, "granted to alpha");
  EXPECT_EQ(reply.value().uuid, "uuid-of-alpha");
  EXPECT_EQ(reply.value().motor_ids, (std::vector<std::int32_t>{1, 2}));
  EXPECT_EQ(reply.value().applied_behavior, Behavior::kDamping);
}

TEST(Service, ClientAndServerOnSeparateParticipantsTalk) {
  const testing::PrivateDomain domain;
  auto server_side = Participant::create(domain.settings());
  auto client_side = Participant::create(domain.settings());
  ASSERT_TRUE(server_side && client_side);
  auto server = Server::create(server_side.value(), kService);
  ASSERT_TRUE(server) << server.error().message;
  const AnsweringServer answering(*server.value(), grant);
  auto client = make_client(client_side.value());
  ASSERT_NE(client, nullptr);

  for (const std::string name : {"first", "second", "third"}) {
    const auto reply = client->call(request_from(name), 2s);
    ASSERT_TRUE(reply) << reply.error().message;
    EXPECT_EQ(reply.value().message, "granted to " + name);
  }
}

TEST(Service, WithoutServerCallIsNotAvailableWithinItsTimeout) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  auto client = make_client(participant.value());
  ASSERT_NE(client, nullptr);

  const auto timeout = 300ms;
  const auto start = Clock::now();
  const auto reply = client->call(request_from("alpha"), timeout);
  const auto elapsed = Clock::now() - start;

  ASSERT_FALSE(reply);
  EXPECT_EQ(reply.error().code, ErrorCode::kNotAvailable);
  EXPECT_NE(reply.error().message.find("/request_control"), std::string::npos) << reply.error().message;
  EXPECT_GE(elapsed, timeout);
  EXPECT_LT(elapsed, timeout + kLateMargin);
}

TEST(Service, SilentServerGivesTimeoutWithinItsTimeout) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  auto server = Server::create(participant.value(), kService);  // never takes or answers a request
  ASSERT_TRUE(server) << server.error().message;
  auto client = make_client(participant.value());
  ASSERT_NE(client, nullptr);

  const auto timeout = 300ms;
  const auto start = Clock::now();
  const auto reply = client->call(request_from("alpha"), timeout);
  const auto elapsed = Clock::now() - start;

  ASSERT_FALSE(reply);
  EXPECT_EQ(reply.error().code, ErrorCode::kTimeout);
  EXPECT_GE(elapsed, timeout);
  EXPECT_LT(elapsed, timeout + kLateMargin);
}

TEST(Service, ConcurrentClientsEachGetTheirOwnReply) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  auto server = Server::create(participant.value(), kService);
  ASSERT_TRUE(server) << server.error().message;
  auto alpha = make_client(participant.value());
  auto beta = make_client(participant.value());
  ASSERT_TRUE(alpha && beta);

  // Both clients send sequence number 1. The server holds both requests and answers them in
  // reverse order, so each client's reply reader first sees the other client's reply: only
  // the guid tells them apart.
  std::jthread answering([&server](const std::stop_token& stop) {
    std::vector<std::pair<RequestId, RequestControlRequest>> pending;
    while (!stop.stop_requested() && pending.size() < 2) {
      server.value()->take_requests(
          [&](const RequestId& id, RequestControlRequest&& request) { pending.emplace_back(id, std::move(request)); });
      std::this_thread::sleep_for(1ms);
    }
    if (pending.size() < 2) return;
    EXPECT_EQ(pending[0].first.sequence_number, pending[1].first.sequence_number);
    EXPECT_NE(pending[0].first.client_guid, pending[1].first.client_guid);
    for (auto it = pending.rbegin(); it != pending.rend(); ++it) {
      EXPECT_TRUE(server.value()->reply(it->first, grant(it->second)));
    }
  });

  auto alpha_reply = std::async(std::launch::async, [&] { return alpha->call(request_from("alpha"), 3s); });
  auto beta_reply = std::async(std::launch::async, [&] { return beta->call(request_from("beta"), 3s); });
  const auto alpha_result = alpha_reply.get();
  const auto beta_result = beta_reply.get();
  ASSERT_TRUE(alpha_result) << alpha_result.error().message;
  ASSERT_TRUE(beta_result) << beta_result.error().message;
  EXPECT_EQ(alpha_result.value().message, "granted to alpha");
  EXPECT_EQ(beta_result.value().message, "granted to beta");
}

TEST(Service, LateReplyToAnEarlierCallIsNotTakenForTheNextOne) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  auto server = Server::create(participant.value(), kService);
  ASSERT_TRUE(server) << server.error().message;
  auto client = make_client(participant.value());
  ASSERT_NE(client, nullptr);

  const auto first = client->call(request_from("first"), 100ms);
  ASSERT_FALSE(first);
  EXPECT_EQ(first.error().code, ErrorCode::kTimeout);

  // The answer to the first call arrives after the client gave up on it...
  std::optional<RequestId> first_id;
  server.value()->take_requests([&](const RequestId& id, RequestControlRequest&&) { first_id = id; });
  ASSERT_TRUE(first_id.has_value());
  RequestControlResponse late = grant(request_from("first"));
  late.message = "late answer to the first call";
  ASSERT_TRUE(server.value()->reply(*first_id, late));

  // ...and must not be mistaken for the answer to the second.
  const AnsweringServer answering(*server.value(), grant);
  const auto second = client->call(request_from("second"), 2s);
  ASSERT_TRUE(second) << second.error().message;
  EXPECT_EQ(second.value().message, "granted to second");
}

TEST(Service, ManyClientsDoNotSlowRepliesDown) {
  // Before replying, the server makes sure the caller's reply reader is matched (up to 100 ms).
  // It must find that reader among all matched ones, not only the first few dozen.
  constexpr int kClients = 80;
  const testing::PrivateDomain domain;
  std::vector<Participant> participants;
  std::vector<std::unique_ptr<Client>> clients;
  for (int i = 0; i < kClients; ++i) {
    auto participant = Participant::create(domain.settings());
    ASSERT_TRUE(participant) << participant.error().message;
    participants.push_back(std::move(participant.value()));
    clients.push_back(make_client(participants.back()));
    ASSERT_NE(clients.back(), nullptr);
  }
  auto server = Server::create(participants.front(), kService);
  ASSERT_TRUE(server) << server.error().message;
  const AnsweringServer answering(*server.value(), grant);

  const auto start = Clock::now();
  for (auto& client : clients) {
    const auto reply = client->call(request_from("client"), 2s);
    ASSERT_TRUE(reply) << reply.error().message;
  }
  // About a millisecond per call; a reply held back 100 ms for even ten clients exceeds this.
  EXPECT_LT(Clock::now() - start, 1s);
}

}  // namespace
}  // namespace robotd::wire
