// Runs the livelybot USB-CDC board host SDK (livelybot_hardware_sdk: motor.cc, canport.cc,
// lively_serial.cc, crc8.cc, crc16.cc) on the host and prints, one JSON object a line, the packets
// its calls write, what its receive loop makes of crafted board packets, and its motor table.
// generate.py compiles this file with the vendor's sources included (so the table's private
// inline conversions can be called) and the stand-ins of board_stubs/.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <variant>
#include <vector>

#include "ros/ros.h"
#include "serial/serial.h"

// The table's conversions (pid_scale, tqe_int2float, …) are private inline members of motor.
#define private public
#include "hardware/canport.cc"
#include "hardware/motor.cc"
#include "lively_serial.cc"
#undef private

namespace ros {
std::map<std::string, ParamValue>& params() {
  static std::map<std::string, ParamValue> map;
  return map;
}
std::function<void()>& sleep_hook() {
  static std::function<void()> hook;
  return hook;
}
}  // namespace ros

namespace serial {
std::function<void(const std::vector<std::uint8_t>&)>& written() {
  static std::function<void(const std::vector<std::uint8_t>&)> callback;
  return callback;
}
std::deque<std::uint8_t>& incoming() {
  static std::deque<std::uint8_t> bytes;
  return bytes;
}
}  // namespace serial

namespace {

std::string hex(const std::vector<std::uint8_t>& bytes) {
  std::string text;
  char buffer[4];
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    std::snprintf(buffer, sizeof buffer, "%s%02x", i ? " " : "", bytes[i]);
    text += buffer;
  }
  return text;
}

std::string number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

// %.9g round-trips a float.
std::string number(float value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.9g", static_cast<double>(value));
  return buffer;
}

/// A board packet as the board would send it: the SDK's own CRC functions frame it.
std::vector<std::uint8_t> board_packet(std::uint8_t command, const std::vector<std::uint8_t>& payload) {
  cdc_tr_message_s message{};
  message.head.s.head = 0xF7;
  message.head.s.cmd = command;
  message.head.s.len = static_cast<std::uint16_t>(payload.size());
  std::memcpy(message.data.data, payload.data(), payload.size());
  message.head.s.crc8 = Get_CRC8_Check_Sum(&message.head.data[1], 3, 0xFF);
  message.head.s.crc16 = crc_ccitt(0xFFFF, message.data.data, message.head.s.len);
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(&message);
  return {bytes, bytes + sizeof(cdc_tr_message_head_s) + payload.size()};
}

struct MotorSpec {
  int id;
  std::string model;
};

/// Destroys an object made in calloc'ed memory.
template <typename T>
struct FreeDelete {
  void operator()(T* object) const {
    object->~T();
    std::free(object);
  }
};

/// One CAN port of board 1 with these motors, as the SDK builds it from its yaml parameters.
struct Port {
  std::unique_ptr<lively_serial, FreeDelete<lively_serial>> serial;
  std::unique_ptr<canport, FreeDelete<canport>> port;
  std::vector<motor*> motors;
  std::vector<std::vector<std::uint8_t>> packets;

  explicit Port(const std::vector<MotorSpec>& specs) {
    auto& params = ros::params();
    params.clear();
    const std::string base = "robot/CANboard/No_1_CANboard/CANport/CANport_1/";
    params[base + "motor_num"] = static_cast<int>(specs.size());
    params["robot/control_type"] = 12;
    for (std::size_t i = 0; i < specs.size(); ++i) {
      const std::string motor_key = base + "motor/motor" + std::to_string(i + 1) + "/";
      params[motor_key + "name"] = "m" + std::to_string(specs[i].id);
      params[motor_key + "id"] = specs[i].id;
      params[motor_key + "type"] = specs[i].model;
      params[motor_key + "num"] = static_cast<int>(i + 1);
      params[motor_key + "pos_limit_enable"] = false;
      params[motor_key + "tor_limit_enable"] = false;
      for (const char* limit : {"pos_upper", "pos_lower", "tor_upper", "tor_lower"}) params[motor_key + limit] = 0.0;
    }
    serial::written() = [this](const std::vector<std::uint8_t>& bytes) { packets.push_back(bytes); };
    std::string tty = "/dev/null";
    serial.reset(new (zeroed(sizeof(lively_serial))) lively_serial(&tty, 4000000));
    port.reset(new (zeroed(sizeof(canport))) canport(1, 1, serial.get()));
    port->puch_motor(&motors);
  }

  // The SDK's objects leave their packet buffer uninitialised (the ROS node makes them once, at
  // start-up, in fresh memory): each port here starts from zeroed memory too, so that no packet
  // of an earlier port is taken for the current mode.
  static void* zeroed(std::size_t size) { return std::calloc(1, size); }

  motor& by_id(int id) {
    for (motor* m : motors) {
      if (m->get_motor_id() == id) return *m;
    }
    std::fprintf(stderr, "no motor %d\n", id);
    std::exit(2);
  }

  std::vector<std::uint8_t> send() {
    packets.clear();
    port->motor_send_2();
    return packets.empty() ? std::vector<std::uint8_t>{} : packets.back();
  }

  /// Feeds bytes to the SDK's receive loop, which returns when they run out.
  void receive(const std::vector<std::uint8_t>& bytes) {
    serial::incoming().assign(bytes.begin(), bytes.end());
    serial->recv_1for6_42();
  }
};

std::string motors_json(const std::vector<MotorSpec>& specs) {
  std::string text = "[";
  for (std::size_t i = 0; i < specs.size(); ++i) {
    text += (i ? "," : "") + std::string("{\"id\":") + std::to_string(specs[i].id) + ",\"model\":\"" + specs[i].model +
            "\"}";
  }
  return text + "]";
}

/// The SDK's model names (its motor_type2 map) in a stable order.
std::vector<std::string> model_names() {
  std::set<std::string> names;
  for (const auto& entry : motor_type2) {
    if (entry.first != "NULL") names.insert(entry.first);
  }
  return {names.begin(), names.end()};
}

// ---- values ---------------------------------------------------------------------------------

std::uint32_t lcg_state = 777;
float uniform(float low, float high) {
  lcg_state = lcg_state * 1664525U + 1013904223U;
  return low + (high - low) * static_cast<float>(lcg_state >> 8) / 16777216.0F;
}

struct Command {
  int motor;
  float position, velocity, torque, kp, kd, acceleration, voltage, current;
  std::int16_t timeout_ms;
};

Command random_command(int motor) {
  return Command{motor,
                 uniform(-20, 20),
                 uniform(-50, 50),
                 uniform(-30, 30),
                 uniform(0, 200),
                 uniform(0, 10),
                 uniform(-30, 30),
                 uniform(-24, 24),
                 uniform(-40, 40),
                 static_cast<std::int16_t>(uniform(0, 1000))};
}

std::string command_json(const Command& c) {
  return "{\"motor\":" + std::to_string(c.motor) + ",\"position\":" + number(c.position) +
         ",\"velocity\":" + number(c.velocity) + ",\"torque\":" + number(c.torque) + ",\"kp\":" + number(c.kp) +
         ",\"kd\":" + number(c.kd) + ",\"acceleration\":" + number(c.acceleration) +
         ",\"voltage\":" + number(c.voltage) + ",\"current\":" + number(c.current) +
         ",\"timeout_ms\":" + std::to_string(c.timeout_ms) + "}";
}

using ModeCall = std::function<void(motor&, const Command&)>;

const std::vector<std::pair<std::string, ModeCall>>& mode_calls() {
  static const std::vector<std::pair<std::string, ModeCall>> calls{
      {"position", [](motor& m, const Command& c) { m.position(c.position); }},
      {"velocity", [](motor& m, const Command& c) { m.velocity(c.velocity); }},
      {"torque", [](motor& m, const Command& c) { m.torque(c.torque); }},
      {"voltage", [](motor& m, const Command& c) { m.voltage(c.voltage); }},
      {"current", [](motor& m, const Command& c) { m.current(c.current); }},
      {"timeout", [](motor& m, const Command& c) { m.set_motorout(c.timeout_ms); }},
      {"pos_vel_tqe", [](motor& m, const Command& c) { m.pos_vel_MAXtqe(c.position, c.velocity, c.torque); }},
      {"pos_vel_tqe_kp_kd",
       [](motor& m, const Command& c) { m.pos_vel_tqe_kp_kd(c.position, c.velocity, c.torque, c.kp, c.kd); }},
      {"pos_vel_tqe_kp_kd2",
       [](motor& m, const Command& c) { m.pos_vel_tqe_kp_kd2(c.position, c.velocity, c.torque, c.kp, c.kd); }},
      {"pos_vel_kp_kd", [](motor& m, const Command& c) { m.pos_vel_kp_kd(c.position, c.velocity, c.kp, c.kd); }},
      {"pos_vel_acc", [](motor& m, const Command& c) { m.pos_vel_acc(c.position, c.velocity, c.acceleration); }},
  };
  return calls;
}

// ---- board packets: one port, several cycles, the SDK's per-port buffer -----------------------

void packet_sequence(const std::string& mode, const ModeCall& call, const std::vector<MotorSpec>& specs,
                     const std::vector<std::vector<int>>& cycles) {
  Port port(specs);
  std::printf("{\"group\":\"board packets\",\"mode\":\"%s\",\"motors\":%s,\"steps\":[", mode.c_str(),
              motors_json(specs).c_str());
  for (std::size_t s = 0; s < cycles.size(); ++s) {
    std::printf("%s{\"commands\":[", s ? "," : "");
    for (std::size_t i = 0; i < cycles[s].size(); ++i) {
      const Command c = random_command(cycles[s][i]);
      call(port.by_id(c.motor), c);
      std::printf("%s%s", i ? "," : "", command_json(c).c_str());
    }
    std::printf("],\"packet\":\"%s\"}", hex(port.send()).c_str());
  }
  std::printf("]}\n");
}

void board_packets() {
  const std::vector<MotorSpec> three{{1, "6056_36"}, {2, "5047_36"}, {3, "4438_32"}};
  const std::vector<MotorSpec> gap{{1, "4538_19"}, {2, "5047_36_2"}, {4, "General"}};
  for (const auto& [mode, call] : mode_calls()) {
    packet_sequence(mode, call, three, {{1, 2, 3}, {2}, {1, 3}, {3}});
    packet_sequence(mode, call, three, {{2}, {2}, {1}});
    packet_sequence(mode, call, gap, {{4}, {1, 2}, {2}});
  }
  // A mode change resets the buffer: the motors not commanded since read as unset again.
  Port port(three);
  std::printf("{\"group\":\"board packets\",\"mode\":\"pos_vel_tqe_kp_kd2 after torque\",\"motors\":%s,\"steps\":[",
              motors_json(three).c_str());
  const Command first = random_command(1);
  port.by_id(1).pos_vel_tqe_kp_kd2(first.position, first.velocity, first.torque, first.kp, first.kd);
  std::printf("{\"mode\":\"pos_vel_tqe_kp_kd2\",\"commands\":[%s],\"packet\":\"%s\"},", command_json(first).c_str(),
              hex(port.send()).c_str());
  const Command second = random_command(2);
  port.by_id(2).torque(second.torque);
  std::printf("{\"mode\":\"torque\",\"commands\":[%s],\"packet\":\"%s\"},", command_json(second).c_str(),
              hex(port.send()).c_str());
  const Command third = random_command(3);
  port.by_id(3).pos_vel_tqe_kp_kd2(third.position, third.velocity, third.torque, third.kp, third.kd);
  std::printf("{\"mode\":\"pos_vel_tqe_kp_kd2\",\"commands\":[%s],\"packet\":\"%s\"}]}\n", command_json(third).c_str(),
              hex(port.send()).c_str());
}

// ---- per-model scaling: 0xB0 payloads over a grid, and replies decoded -----------------------

void model_scaling(const std::string& model) {
  Port port({{1, model}});
  motor& m = port.by_id(1);
  const double k = m.tqe_int2float(10000, m.get_motor_enum_type()) - m.tqe_int2float(0, m.get_motor_enum_type());
  const float torque_span = static_cast<float>(32767 * k / 10000.0);
  std::vector<Command> grid;
  const float fixed[][5] = {{0, 0, 0, 0, 0},
                            {0.35F, 0.7F, 0.35F, 10, 0.7F},
                            {-0.35F, -0.7F, -0.35F, 40, 1},
                            {1, 1, 1, 100, 2.8F},
                            {3.1415927F, 10, 5, 300, 20},
                            {-3.1415927F, -10, -5, 0.1F, 0.1F},
                            {20.58F, 51.4F, 0, 1000, 50},
                            {-20.58F, -51.4F, 0, 60, 0.3F},
                            {21, 52, 0, 5, 5},
                            {-21, -52, 0, 5, 5}};
  for (const auto& f : fixed) grid.push_back(Command{1, f[0], f[1], f[2], f[3], f[4], 0, 0, 0, 0});
  for (const float t : {torque_span * 0.99F, -torque_span * 0.99F, torque_span * 1.02F, -torque_span * 1.02F}) {
    grid.push_back(Command{1, 0, 0, t, 0, 0, 0, 0, 0, 0});
  }
  for (int i = 0; i < 24; ++i) {
    Command c = random_command(1);
    c.torque = uniform(-torque_span * 0.9F, torque_span * 0.9F);
    c.kp = uniform(0, 300);
    c.kd = uniform(0, 20);
    grid.push_back(c);
  }
  for (const Command& c : grid) {
    m.pos_vel_tqe_kp_kd2(c.position, c.velocity, c.torque, c.kp, c.kd);
    std::printf("{\"group\":\"board scaling\",\"model\":\"%s\",\"command\":%s,\"packet\":\"%s\"}\n", model.c_str(),
                command_json(c).c_str(), hex(port.send()).c_str());
  }
}

// ---- replies: crafted board packets through the SDK's receive loop ---------------------------

void put16(std::vector<std::uint8_t>& bytes, std::int16_t value) {
  bytes.push_back(static_cast<std::uint8_t>(value & 0xFF));
  bytes.push_back(static_cast<std::uint8_t>((value >> 8) & 0xFF));
}

void reply_vector(const std::vector<MotorSpec>& specs, std::uint8_t command, const std::vector<std::uint8_t>& payload,
                  bool corrupt = false) {
  Port port(specs);
  for (motor* m : port.motors) {
    motor_back_t* state = m->get_current_motor_state();
    state->mode = 0xEE;
    state->fault = 0xEE;
    state->position = state->velocity = state->torque = 12345.0F;
  }
  std::vector<std::uint8_t> bytes = board_packet(command, payload);
  if (corrupt) bytes.back() ^= 0x01;
  port.receive(bytes);
  std::printf("{\"group\":\"board replies\",\"motors\":%s,\"packet\":\"%s\",\"vendor\":[", motors_json(specs).c_str(),
              hex(bytes).c_str());
  for (std::size_t i = 0; i < port.motors.size(); ++i) {
    motor* m = port.motors[i];
    const motor_back_t* s = m->get_current_motor_state();
    const cdc_rx_motor_version_s& v = m->get_version();
    std::printf(
        "%s{\"id\":%d,\"mode\":%d,\"fault\":%d,\"position\":%s,\"velocity\":%s,\"torque\":%s,"
        "\"version\":[%d,%d,%d]}",
        i ? "," : "", m->get_motor_id(), s->mode, s->fault, number(s->position).c_str(), number(s->velocity).c_str(),
        number(s->torque).c_str(), v.major, v.minor, v.patch);
  }
  std::printf("]}\n");
}

void board_replies() {
  const std::vector<MotorSpec> three{{1, "6056_36"}, {2, "5047_36"}, {3, "4438_32"}};
  const std::int16_t raws[][3] = {{0, 0, 0},
                                  {1, -1, 2},
                                  {10000, 4000, 100},
                                  {-10000, -4000, -100},
                                  {32767, 32767, 32767},
                                  {-32767, -32767, -32767},
                                  {-32768, -32768, -32768},
                                  {1234, -5678, 910}};
  for (const auto& raw : raws) {
    for (const std::uint8_t command : {std::uint8_t{MODE_MOTOR_STATE}, std::uint8_t{MODE_MOTOR_STATE2}}) {
      std::vector<std::uint8_t> payload;
      for (int id = 3; id >= 1; --id) {  // records need not be in id order
        payload.push_back(static_cast<std::uint8_t>(id));
        if (command == MODE_MOTOR_STATE2) {
          payload.push_back(0x21);
          payload.push_back(static_cast<std::uint8_t>(id == 2 ? 0x14 : 0));
        }
        put16(payload, raw[0]);
        put16(payload, raw[1]);
        put16(payload, raw[2]);
      }
      reply_vector(three, command, payload);
    }
  }
  // Every model decodes the same raw torques through its own table.
  for (const std::string& model : model_names()) {
    for (const std::int16_t raw :
         {std::int16_t{0}, std::int16_t{1000}, std::int16_t{-1000}, std::int16_t{32767}, std::int16_t{-32768}}) {
      std::vector<std::uint8_t> payload{1, 0x21, 0};
      put16(payload, raw);
      put16(payload, raw);
      put16(payload, raw);
      reply_vector({{1, model}}, MODE_MOTOR_STATE2, payload);
    }
  }
  // A record for a motor the port does not have, and a packet whose CRC-16 fails.
  std::vector<std::uint8_t> stranger{7, 0x21, 0};
  put16(stranger, 5000), put16(stranger, 5000), put16(stranger, 5000);
  reply_vector(three, MODE_MOTOR_STATE2, stranger);
  std::vector<std::uint8_t> corrupt{1, 0x21, 0};
  put16(corrupt, 5000), put16(corrupt, 5000), put16(corrupt, 5000);
  reply_vector(three, MODE_MOTOR_STATE2, corrupt, true);
  // Motor versions (0x0B): id, major, minor, patch.
  reply_vector(three, MODE_MOTOR_VERSION, {1, 4, 4, 6, 2, 4, 2, 3, 3, 5, 0, 1});
}

// ---- the motor table ----------------------------------------------------------------------

void motor_table() {
  for (const std::string& model : model_names()) {
    Port port({{1, model}});
    motor& m = port.by_id(1);
    const motor_type type = m.get_motor_enum_type();
    const double d = m.tqe_int2float(0, type);
    const double k = (m.tqe_int2float(10000, type) - d) / 10000.0;
    const double k_pid = 1.0 / m.pid_scale(1.0F, type);
    std::printf(
        "{\"group\":\"board models\",\"model\":\"%s\",\"torque_per_unit\":%s,\"torque_offset_nm\":%s,"
        "\"gain_factor\":%s}\n",
        model.c_str(), number(k).c_str(), number(d).c_str(), number(k_pid).c_str());
  }
}

// ---- admin packets and the acknowledged commands, against an emulated board -----------------

struct EmulatedBoard {
  std::vector<std::string> transcript;  // "host: …" / "board: …"
  int attempts = 0;
  std::set<int> answering;  // motors that acknowledge from the second attempt on
  std::vector<int> first_answer;
  std::deque<std::uint8_t> pending;

  void on_packet(const std::vector<std::uint8_t>& bytes) {
    transcript.push_back("host " + hex(bytes));
    const std::uint8_t command = bytes[1];
    std::vector<std::uint8_t> reply;
    if (command == MODE_RESET_ZERO || command == MODE_CONF_WRITE || command == MODE_CONF_LOAD) {
      const std::vector<int>& ids =
          attempts++ == 0 ? first_answer : std::vector<int>(answering.begin(), answering.end());
      std::vector<std::uint8_t> payload(ids.begin(), ids.end());
      reply = board_packet(command, payload);
    } else if (command == MODE_SET_NUM) {
      reply = board_packet(command, {bytes[7], 0, 4, 3});  // board firmware 4.3
    } else if (command == MODE_FUN_V) {
      reply = board_packet(command, {bytes[7]});
    }
    if (!reply.empty()) {
      transcript.push_back("board " + hex(reply));
      pending.insert(pending.end(), reply.begin(), reply.end());
    }
  }
};

void acknowledged(const std::string& call, const std::function<int(canport&)>& run,
                  const std::vector<int>& first_answer) {
  const std::vector<MotorSpec> specs{{1, "6056_36"}, {2, "5047_36"}, {3, "4438_32"}};
  Port port(specs);
  EmulatedBoard board;
  board.first_answer = first_answer;
  board.answering = {1, 2, 3};
  serial::written() = [&board](const std::vector<std::uint8_t>& bytes) { board.on_packet(bytes); };
  ros::sleep_hook() = [&] {
    if (board.pending.empty()) return;
    port.receive(std::vector<std::uint8_t>(board.pending.begin(), board.pending.end()));
    board.pending.clear();
  };
  const int result = run(*port.port);
  ros::sleep_hook() = nullptr;
  std::printf("{\"group\":\"board start-up\",\"call\":\"%s\",\"motors\":%s,\"result\":%d,\"transcript\":[",
              call.c_str(), motors_json(specs).c_str(), result);
  for (std::size_t i = 0; i < board.transcript.size(); ++i) {
    std::printf("%s\"%s\"", i ? "," : "", board.transcript[i].c_str());
  }
  std::printf("]}\n");
}

void admin_packets() {
  const std::vector<MotorSpec> specs{{1, "6056_36"}, {2, "5047_36"}, {3, "4438_32"}};
  const std::vector<std::pair<std::string, std::function<void(canport&)>>> calls{
      {"stop", [](canport& p) { p.set_stop(), p.motor_send_2(); }},
      {"reset", [](canport& p) { p.set_reset(), p.motor_send_2(); }},
      {"state", [](canport& p) { p.send_get_motor_state_cmd(); }},
      {"state2", [](canport& p) { p.send_get_motor_state_cmd2(); }},
      {"version", [](canport& p) { p.send_get_motor_version_cmd(); }},
      {"runzero", [](canport& p) { p.set_motor_runzero(); }},
      {"timeout 200", [](canport& p) { p.set_time_out(200); }},
      {"timeout 0", [](canport& p) { p.set_time_out(0); }},
      {"fdcan reset", [](canport& p) { p.canboard_fdcan_reset(); }},
  };
  for (const auto& [name, call] : calls) {
    Port port(specs);
    call(*port.port);
    std::printf("{\"group\":\"board admin packets\",\"call\":\"%s\",\"motors\":%s,\"packets\":[", name.c_str(),
                motors_json(specs).c_str());
    for (std::size_t i = 0; i < port.packets.size(); ++i) {
      std::printf("%s\"%s\"", i ? "," : "", hex(port.packets[i]).c_str());
    }
    std::printf("]}\n");
  }
  acknowledged("set_reset_zero", [](canport& p) { return p.set_reset_zero(); }, {1, 3});
  acknowledged("set_reset_zero 2", [](canport& p) { return p.set_reset_zero(2); }, {});
  acknowledged("set_conf_write", [](canport& p) { return p.set_conf_write(2); }, {2});
  acknowledged("set_conf_load", [](canport& p) { return p.set_conf_load(); }, {2, 3});
  acknowledged("set_motor_num", [](canport& p) { return static_cast<int>(p.set_motor_num() * 10); }, {});
  acknowledged("set_fun_v", [](canport& p) { return p.set_fun_v(fun_v5), 0; }, {});
}

}  // namespace

int main() {
  board_packets();
  for (const std::string& model : model_names()) model_scaling(model);
  board_replies();
  motor_table();
  admin_packets();
  return 0;
}
