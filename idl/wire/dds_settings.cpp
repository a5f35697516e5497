#include "wire/dds_settings.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string_view>
#include <system_error>

#include "wire/dds_security.hpp"

namespace robotd::wire {
namespace {

std::string xml_escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Cyclone takes a URI; an absolute path keeps it independent of the working directory.
std::string file_uri(const std::string& path) {
  std::error_code error;
  const auto absolute = std::filesystem::absolute(path, error);
  return "file:" + xml_escape(error ? path : absolute.string());
}

// Cyclone's built-in plugins by their plain names: Cyclone finds them next to libddsc (Debian's
// package looks in its libddsc0debian directory).
void write_security(std::ostream& xml, const DdsSecurityFiles& files) {
  xml << "<Security><Authentication>"
      << "<Library path=\"dds_security_auth\" initFunction=\"init_authentication\" "
         "finalizeFunction=\"finalize_authentication\"/>"
      << "<IdentityCA>" << file_uri(files.identity_ca) << "</IdentityCA>"
      << "<IdentityCertificate>" << file_uri(files.identity_certificate) << "</IdentityCertificate>"
      << "<PrivateKey>" << file_uri(files.private_key) << "</PrivateKey></Authentication>"
      << "<AccessControl>"
      << "<Library path=\"dds_security_ac\" initFunction=\"init_access_control\" "
         "finalizeFunction=\"finalize_access_control\"/>"
      << "<PermissionsCA>" << file_uri(files.permissions_ca) << "</PermissionsCA>"
      << "<Governance>" << file_uri(files.governance) << "</Governance>"
      << "<Permissions>" << file_uri(files.permissions) << "</Permissions></AccessControl>"
      << "<Cryptographic>"
      << "<Library path=\"dds_security_crypto\" initFunction=\"init_crypto\" finalizeFunction=\"finalize_crypto\"/>"
      << "</Cryptographic></Security>";
}

// Cyclone 0.10 accepts properties only for these thread names ("unknown thread" otherwise); the
// per-socket receive threads (recvUC, recvMC) that MultipleReceiveThreads starts are not among
// them, which is one more reason robotd runs a single receive thread.
constexpr std::array<std::string_view, 6> kCycloneThreads{"recv", "tev", "gc", "dq.builtins", "dq.user", "fsm"};

void write_threads(std::ostream& xml, const DdsSettings& settings) {
  if (settings.receive_thread_priority <= 0 && settings.thread_stack_bytes == 0) return;
  xml << "<Threads>";
  for (const std::string_view name : kCycloneThreads) {
    const bool scheduled = name == "recv" && settings.receive_thread_priority > 0;
    if (!scheduled && settings.thread_stack_bytes == 0) continue;
    xml << "<Thread Name=\"" << name << "\">";
    if (scheduled) {
      xml << "<Scheduling><Class>realtime</Class><Priority>" << settings.receive_thread_priority
          << "</Priority></Scheduling>";
    }
    if (settings.thread_stack_bytes > 0) xml << "<StackSize>" << settings.thread_stack_bytes << "B</StackSize>";
    xml << "</Thread>";
  }
  xml << "</Threads>";
}

bool looks_like_address(std::string_view text) {
  return !text.empty() && text.find_first_not_of("0123456789.:abcdefABCDEF") == std::string_view::npos &&
         (text.find('.') != std::string_view::npos || text.find(':') != std::string_view::npos);
}

}  // namespace

std::string to_cyclone_xml(const DdsSettings& settings) {
  if (!settings.cyclonedds_xml.empty()) return settings.cyclonedds_xml;
  std::ostringstream xml;
  xml << "<CycloneDDS><Domain id=\"any\"><General>";
  if (!settings.network_interface.empty()) {
    const char* attribute = looks_like_address(settings.network_interface) ? "address" : "name";
    xml << "<Interfaces><NetworkInterface " << attribute << "=\"" << xml_escape(settings.network_interface)
        << "\"/></Interfaces>";
  }
  xml << "<AllowMulticast>" << (settings.multicast ? "true" : "false") << "</AllowMulticast></General>";
  xml << "<Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>"
      << settings.max_participant_index << "</MaxAutoParticipantIndex>";
  if (!settings.peers.empty()) {
    xml << "<Peers>";
    for (const auto& peer : settings.peers) xml << "<Peer address=\"" << xml_escape(peer) << "\"/>";
    xml << "</Peers>";
  }
  xml << "</Discovery>";
  if (settings.receive_thread_priority > 0) {
    xml << "<Internal><MultipleReceiveThreads>false</MultipleReceiveThreads></Internal>";
  }
  write_threads(xml, settings);
  if (settings.security.enabled()) write_security(xml, settings.security);
  xml << "</Domain></CycloneDDS>";
  return xml.str();
}

DdsSettings dds_settings_from_environment() {
  DdsSettings settings;
  if (const char* id = std::getenv("ROBOTD_DOMAIN_ID"); id != nullptr && *id != '\0') {
    const std::string_view text(id);
    int value = -1;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc{} || end != text.data() + text.size() || value < 0) {
      // Never fall back to domain 0: that could be another robot's. -1 makes connecting fail.
      std::cerr << "robotd: ROBOTD_DOMAIN_ID='" << text << "' is not a DDS domain id (expected a whole number 0..230)"
                << std::endl;
      value = -1;
    }
    settings.domain_id = value;
  }
  if (const char* iface = std::getenv("ROBOTD_DDS_INTERFACE"); iface != nullptr) {
    settings.network_interface = iface;
  }
  if (const char* peers = std::getenv("ROBOTD_DDS_PEERS"); peers != nullptr) {
    settings.peers.clear();
    std::stringstream list(peers);
    for (std::string peer; std::getline(list, peer, ',');) {
      if (!peer.empty()) settings.peers.push_back(peer);
    }
  }
  if (const char* multicast = std::getenv("ROBOTD_DDS_MULTICAST"); multicast != nullptr) {
    settings.multicast = std::string_view(multicast) == "1" || std::string_view(multicast) == "true";
  }
  for (const auto& field : kSecurityFileFields) {
    std::string variable = "ROBOTD_DDS_SECURITY_" + std::string(field.name);
    std::transform(variable.begin(), variable.end(), variable.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    if (const char* path = std::getenv(variable.c_str()); path != nullptr) settings.security.*field.path = path;
  }
  return settings;
}

}  // namespace robotd::wire
