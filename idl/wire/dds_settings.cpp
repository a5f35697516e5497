#include "wire/dds_settings.hpp"

#include <cstdlib>
#include <sstream>
#include <string_view>

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
  xml << "</Discovery></Domain></CycloneDDS>";
  return xml.str();
}

DdsSettings dds_settings_from_environment() {
  DdsSettings settings;
  if (const char* id = std::getenv("ROBOTD_DOMAIN_ID"); id != nullptr && *id != '\0') {
    settings.domain_id = std::atoi(id);
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
  return settings;
}

}  // namespace robotd::wire
