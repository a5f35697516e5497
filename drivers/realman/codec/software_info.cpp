// Which arm and firmware the controller is (§4): get_arm_software_info on gen 3/4 controllers,
// get_arm_software_version on gen 2.
#include <cstdint>
#include <ios>
#include <sstream>
#include <string>

#include "field_reader.hpp"
#include "realman_codec.hpp"

namespace robotd::realman {
namespace {

/// Gen 2's Plan_version is read in hex: high byte the model code, low 16 bits the version.
std::string hex_text(std::int64_t value) {
  std::ostringstream out;
  out << "0x" << std::hex << std::uppercase << value;
  return out.str();
}

}  // namespace

Result<SoftwareInfo> parse_software_info(const Message& reply) {
  std::string problem;
  FieldReader body(reply.body, "", problem);
  SoftwareInfo info;
  if (reply.key == "arm_software_info") {
    info.product_version = body.text("Product_version");
    // Gen 4 names the controller version at the top; gen 3 only inside ctrl_info.
    if (body.has("robot_controller_version")) {
      info.controller_version = body.text("robot_controller_version");
    } else if (body.has("ctrl_info")) {
      info.controller_version = body.object("ctrl_info").text("version");
    }
  } else if (reply.key == "arm_software_version") {
    info.product_version = body.text("Product_version");
    info.controller_version = hex_text(body.integer("Plan_version", 0, 0xFFFFFFFF));
  } else {
    return make_error(ErrorCode::kInvalidArgument,
                      "\"" + reply.key + "\" is not a software info reply (arm_software_info, arm_software_version)");
  }
  if (!problem.empty()) return make_error(ErrorCode::kInvalidArgument, reply.key + " reply: " + problem);
  return info;
}

}  // namespace robotd::realman
