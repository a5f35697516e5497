#include "push_config.hpp"

#include <arpa/inet.h>

namespace robotd::realman::sim {

PushConfig PushConfig::updated(const CommandRequest& request) const {
  PushConfig next = *this;
  if (auto value = request.optional_integer("cycle", 1, kMaxCycle)) next.cycle = static_cast<int>(*value);
  if (auto value = request.optional_boolean("enable")) next.enable = *value;
  if (auto value = request.optional_integer("port", 1, 65535)) next.port = static_cast<int>(*value);
  if (auto value = request.optional_integer("force_coordinate", 0, 2)) next.force_coordinate = static_cast<int>(*value);
  if (request.has("ip")) {
    const std::string text = request.string("ip");
    in_addr address{};
    if (!text.empty() && inet_pton(AF_INET, text.c_str(), &address) != 1) {
      throw Refusal("\"ip\" must be a dotted IPv4 address (\"\" for the TCP client's address), got \"" + text + "\"");
    }
    next.ip = text;
  }
  if (request.has("custom")) {
    for (const auto& [key, value] : request.object("custom").items()) {
      const auto known = next.custom.find(key);
      if (known == next.custom.end()) throw Refusal("\"custom\" has no key \"" + key + "\"");
      if (!value.is_boolean()) throw Refusal("\"custom\".\"" + key + "\" must be true or false, got " + value.dump());
      known->second = value.get<bool>();
    }
  }
  return next;
}

nlohmann::json PushConfig::fields() const {
  return {{"cycle", cycle},  {"enable", enable}, {"port", port}, {"ip", ip}, {"force_coordinate", force_coordinate},
          {"custom", custom}};
}

}  // namespace robotd::realman::sim
