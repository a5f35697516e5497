// DdsSettings → Cyclone XML: by default every packet stays on loopback; a deployment names an
// interface (by address or by name), enables multicast or lists peers, or brings its own XML.
#include "wire/dds_settings.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sched.h>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "wire/participant.hpp"
#include "wire_test_support.hpp"

namespace robotd::wire {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(ToCycloneXml, DefaultsKeepTrafficOnLoopback) {
  const std::string xml = to_cyclone_xml(DdsSettings{});
  EXPECT_THAT(xml, HasSubstr("<NetworkInterface address=\"127.0.0.1\"/>"));
  EXPECT_THAT(xml, HasSubstr("<AllowMulticast>false</AllowMulticast>"));
  EXPECT_THAT(xml, HasSubstr("<Peers><Peer address=\"127.0.0.1\"/></Peers>"));
  EXPECT_THAT(xml, HasSubstr("<ParticipantIndex>auto</ParticipantIndex>"));
  EXPECT_THAT(xml, Not(HasSubstr("name=")));
}

TEST(ToCycloneXml, InterfaceNameIsWrittenAsName) {
  DdsSettings settings;
  settings.network_interface = "eth0";
  const std::string xml = to_cyclone_xml(settings);
  EXPECT_THAT(xml, HasSubstr("<NetworkInterface name=\"eth0\"/>"));
  EXPECT_THAT(xml, Not(HasSubstr("address=\"eth0\"")));
}

TEST(ToCycloneXml, InterfaceAddressIsWrittenAsAddress) {
  DdsSettings settings;
  settings.network_interface = "192.168.10.2";
  EXPECT_THAT(to_cyclone_xml(settings), HasSubstr("<NetworkInterface address=\"192.168.10.2\"/>"));
}

TEST(ToCycloneXml, EmptyInterfaceLetsCyclonePick) {
  DdsSettings settings;
  settings.network_interface.clear();
  EXPECT_THAT(to_cyclone_xml(settings), Not(HasSubstr("NetworkInterface")));
}

TEST(ToCycloneXml, MulticastWithoutPeers) {
  DdsSettings settings;
  settings.multicast = true;
  settings.peers.clear();
  const std::string xml = to_cyclone_xml(settings);
  EXPECT_THAT(xml, HasSubstr("<AllowMulticast>true</AllowMulticast>"));
  EXPECT_THAT(xml, Not(HasSubstr("<Peers>")));
}

TEST(ToCycloneXml, ListsEveryPeer) {
  DdsSettings settings;
  settings.peers = {"10.0.0.1", "robot-2.local"};
  EXPECT_THAT(to_cyclone_xml(settings),
              HasSubstr("<Peers><Peer address=\"10.0.0.1\"/><Peer address=\"robot-2.local\"/></Peers>"));
}

TEST(ToCycloneXml, EscapesXmlSpecialCharacters) {
  DdsSettings settings;
  settings.network_interface = "a\"b<c>&";
  EXPECT_THAT(to_cyclone_xml(settings), HasSubstr("name=\"a&quot;b&lt;c&gt;&amp;\""));
}

TEST(ToCycloneXml, ExplicitXmlOverridesEverything) {
  DdsSettings settings;
  settings.network_interface = "eth0";
  settings.multicast = true;
  settings.cyclonedds_xml = "<CycloneDDS><Domain id=\"any\"/></CycloneDDS>";
  EXPECT_EQ(to_cyclone_xml(settings), settings.cyclonedds_xml);
}

TEST(ToCycloneXml, SecurityFilesBecomeTheDomainsSecuritySection) {
  DdsSettings settings;
  settings.security = DdsSecurityFiles{.identity_ca = "/pki/operator/identity_ca.pem",
                                       .identity_certificate = "/pki/operator/identity_certificate.pem",
                                       .private_key = "/pki/operator/private_key.pem",
                                       .permissions_ca = "/pki/operator/permissions_ca.pem",
                                       .governance = "/pki/operator/governance.p7s",
                                       .permissions = "/pki/operator/permissions.p7s"};
  const std::string xml = to_cyclone_xml(settings);
  EXPECT_THAT(xml, HasSubstr("<Security><Authentication><Library path=\"dds_security_auth\" "
                             "initFunction=\"init_authentication\" finalizeFunction=\"finalize_authentication\"/>"
                             "<IdentityCA>file:/pki/operator/identity_ca.pem</IdentityCA>"
                             "<IdentityCertificate>file:/pki/operator/identity_certificate.pem</IdentityCertificate>"
                             "<PrivateKey>file:/pki/operator/private_key.pem</PrivateKey></Authentication>"));
  EXPECT_THAT(xml, HasSubstr("<PermissionsCA>file:/pki/operator/permissions_ca.pem</PermissionsCA>"
                             "<Governance>file:/pki/operator/governance.p7s</Governance>"
                             "<Permissions>file:/pki/operator/permissions.p7s</Permissions></AccessControl>"));
  EXPECT_THAT(xml, HasSubstr("<Cryptographic><Library path=\"dds_security_crypto\""));
  EXPECT_THAT(xml, HasSubstr("</Security></Domain></CycloneDDS>"));
}

TEST(ToCycloneXml, RelativeSecurityPathsBecomeAbsolute) {
  DdsSettings settings;
  settings.security.identity_ca = "pki/identity_ca.pem";
  EXPECT_THAT(to_cyclone_xml(settings),
              HasSubstr("<IdentityCA>file:" + std::filesystem::current_path().string() + "/pki/identity_ca.pem<"));
}

TEST(ToCycloneXml, ReceiveThreadPriorityGivesOneRealtimeReceiveThread) {
  DdsSettings settings;
  settings.receive_thread_priority = 7;
  const std::string xml = to_cyclone_xml(settings);
  EXPECT_THAT(xml, HasSubstr("<MultipleReceiveThreads>false</MultipleReceiveThreads>"));
  EXPECT_THAT(xml, HasSubstr("<Thread Name=\"recv\"><Scheduling><Class>realtime</Class><Priority>7</Priority>"));
  EXPECT_THAT(to_cyclone_xml(DdsSettings{}), Not(HasSubstr("<Threads>")));
}

TEST(ToCycloneXml, ThreadStackSizeGoesToEveryCycloneThread) {
  DdsSettings settings;
  settings.receive_thread_priority = 7;
  settings.thread_stack_bytes = 65536;
  const std::string xml = to_cyclone_xml(settings);
  EXPECT_THAT(xml, HasSubstr("<Thread Name=\"recv\"><Scheduling><Class>realtime</Class><Priority>7</Priority>"
                             "</Scheduling><StackSize>65536B</StackSize></Thread>"));
  for (const char* name : {"tev", "gc", "dq.builtins", "dq.user", "fsm"}) {
    EXPECT_THAT(xml, HasSubstr(std::string("<Thread Name=\"") + name + "\"><StackSize>65536B</StackSize></Thread>"));
  }
  settings.receive_thread_priority = 0;
  EXPECT_THAT(to_cyclone_xml(settings), HasSubstr("<Thread Name=\"recv\"><StackSize>65536B</StackSize></Thread>"));
}

TEST(ToCycloneXml, NoSecurityFilesNoSecuritySection) {
  EXPECT_THAT(to_cyclone_xml(DdsSettings{}), Not(HasSubstr("Security")));
}

// The environment lets tools follow the daemon's deployment. Each CTest test is its own
// process and no other thread runs while it changes the environment, so setenv is safe here.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value, 1);  // NOLINT(concurrency-mt-unsafe)
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;
  ~ScopedEnv() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);  // NOLINT(concurrency-mt-unsafe)
    } else {
      unsetenv(name_);  // NOLINT(concurrency-mt-unsafe)
    }
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(DdsSettingsFromEnvironment, ReadsDomainInterfacePeersAndMulticast) {
  const ScopedEnv domain("ROBOTD_DOMAIN_ID", "42");
  const ScopedEnv iface("ROBOTD_DDS_INTERFACE", "enp3s0");
  const ScopedEnv peers("ROBOTD_DDS_PEERS", "10.0.0.1,,10.0.0.2");
  const ScopedEnv multicast("ROBOTD_DDS_MULTICAST", "1");
  const DdsSettings settings = dds_settings_from_environment();
  EXPECT_EQ(settings.domain_id, 42);
  EXPECT_EQ(settings.network_interface, "enp3s0");
  EXPECT_EQ(settings.peers, (std::vector<std::string>{"10.0.0.1", "10.0.0.2"}));
  EXPECT_TRUE(settings.multicast);
}

TEST(DdsSettingsFromEnvironment, MalformedDomainIdIsNeverDomainZero) {
  for (const char* malformed : {"abc", "7x", "-3", "99999999999"}) {
    const ScopedEnv id("ROBOTD_DOMAIN_ID", malformed);
    ::testing::internal::CaptureStderr();
    const DdsSettings settings = dds_settings_from_environment();
    const std::string said = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(settings.domain_id, -1) << malformed;
    EXPECT_NE(said.find("ROBOTD_DOMAIN_ID='" + std::string(malformed) + "' is not a DDS domain id"), std::string::npos)
        << said;
    EXPECT_FALSE(Participant::create(settings)) << "connecting must fail, not pick a domain";
  }
}

TEST(DdsSettingsFromEnvironment, ReadsTheDdsSecurityFiles) {
  const ScopedEnv ca("ROBOTD_DDS_SECURITY_IDENTITY_CA", "/pki/operator/identity_ca.pem");
  const ScopedEnv permissions("ROBOTD_DDS_SECURITY_PERMISSIONS", "/pki/operator/permissions.p7s");
  const DdsSettings settings = dds_settings_from_environment();
  EXPECT_TRUE(settings.security.enabled());
  EXPECT_EQ(settings.security.identity_ca, "/pki/operator/identity_ca.pem");
  EXPECT_EQ(settings.security.permissions, "/pki/operator/permissions.p7s");
  EXPECT_TRUE(settings.security.private_key.empty());
}

TEST(DdsSettingsFromEnvironment, NoSecurityVariablesLeaveDdsSecurityOff) {
  EXPECT_FALSE(dds_settings_from_environment().security.enabled());
}

TEST(Participant, RejectsDomainIdOutOfRange) {
  DdsSettings settings;
  settings.domain_id = 231;
  const auto participant = Participant::create(settings);
  ASSERT_FALSE(participant);
  EXPECT_EQ(participant.error().code, ErrorCode::kInvalidArgument);
}

TEST(Participant, ReceiveThreadPriorityPutsCyclonesReceiveThreadOnSchedFifo) {
  if (geteuid() != 0) GTEST_SKIP() << "SCHED_FIFO needs root here";
  const testing::PrivateDomain domain;
  DdsSettings settings = domain.settings();
  settings.receive_thread_priority = 3;
  auto participant = Participant::create(settings);
  ASSERT_TRUE(participant) << participant.error().message;
  // Each thread names itself once it runs: wait for the receive thread's name.
  std::vector<std::pair<std::string, pid_t>> receive_threads;
  const auto find_receive_threads = [&] {
    receive_threads.clear();
    for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
      std::ifstream comm(task.path() / "comm");
      std::string name;
      std::getline(comm, name);
      if (name.starts_with("recv")) receive_threads.emplace_back(name, std::stol(task.path().filename().string()));
    }
    return !receive_threads.empty();
  };
  EXPECT_TRUE(testing::wait_until(find_receive_threads));
  ASSERT_EQ(receive_threads.size(), 1U) << "one receive thread for every socket";
  EXPECT_EQ(receive_threads[0].first, "recv");
  const pid_t tid = receive_threads[0].second;
  sched_param param{};
  EXPECT_EQ(sched_getscheduler(tid), SCHED_FIFO);
  ASSERT_EQ(sched_getparam(tid, &param), 0);
  EXPECT_EQ(param.sched_priority, 3);
}

TEST(Participant, MissingInterfaceIsAnErrorNamingIt) {
  const testing::PrivateDomain domain;
  DdsSettings settings = domain.settings();
  settings.network_interface = "robotd-none0";
  const auto participant = Participant::create(settings);
  ASSERT_FALSE(participant);
  EXPECT_EQ(participant.error().code, ErrorCode::kTransport);
  EXPECT_THAT(participant.error().message, HasSubstr("robotd-none0"));
}

}  // namespace
}  // namespace robotd::wire
