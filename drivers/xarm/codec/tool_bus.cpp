// The tool's RS-485 bus (register 124: Modbus RTU frames without their CRC, after the tool board's
// host id) and the direct tool register access of registers 127–130, both directions.
#include <cstddef>
#include <cstdint>
#include <string>

#include "wire_fields.hpp"
#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

constexpr std::uint8_t kModbusExceptionBit = 0x80;
constexpr std::size_t kReadHeaderBytes = 4;         // host id, slave, function, byte count
constexpr std::size_t kWriteEchoBytes = 7;          // host id, slave, function, address, count
constexpr std::size_t kRequestHeaderBytes = 7;      // host id, slave, function, address, count
constexpr std::size_t kToolRegisterReadBytes = 3;   // id, address
constexpr std::size_t kToolRegisterWriteBytes = 7;  // id, address, fp32
constexpr std::size_t kToolRegisterValueBytes = 4;

std::string hex16(std::uint16_t value) {
  constexpr std::string_view kDigits = "0123456789ABCDEF";
  std::string text = "0x0000";
  for (std::size_t i = 0; i < 4; ++i) text[5 - i] = kDigits[(value >> (4 * i)) & 0xF];
  return text;
}

Bytes modbus_head(std::uint8_t slave, std::uint8_t function, std::uint16_t address, std::uint16_t count) {
  return ByteWriter().u8(kToolHostId).u8(slave).u8(function).u16_be(address).u16_be(count).take();
}

/// The device and function a reply names, or the Modbus exception it carries.
Result<void> check_reply_head(ByteView data, std::uint8_t slave, std::uint8_t function, std::size_t expected) {
  if (data.size() >= 4 && data[1] == slave && data[2] == (function | kModbusExceptionBit)) {
    return make_error(ErrorCode::kInvalidArgument, "tool device " + std::to_string(slave) +
                                                       " answered Modbus exception " + std::to_string(data[3]) +
                                                       " to function " + std::to_string(function));
  }
  if (data.size() < expected) return size_error("tool_modbus_rtu reply", "data byte", data.size(), expected, false);
  if (data[0] != kToolHostId || data[1] != slave || data[2] != function) {
    return make_error(ErrorCode::kInvalidArgument,
                      "tool_modbus_rtu reply is from host " + std::to_string(data[0]) + ", device " +
                          std::to_string(data[1]) + ", function " + std::to_string(data[2]) + "; expected host " +
                          std::to_string(kToolHostId) + ", device " + std::to_string(slave) + ", function " +
                          std::to_string(function));
  }
  return {};
}

}  // namespace

Request tool_modbus_read_request(std::uint8_t slave, std::uint16_t address, std::uint16_t count) {
  return Request{.reg = number(Register::kToolModbus),
                 .params = modbus_head(slave, kModbusReadHolding, address, count)};
}

Request tool_modbus_write_request(std::uint8_t slave, std::uint16_t address, std::span<const std::uint16_t> values) {
  ByteWriter writer;
  writer.bytes(modbus_head(slave, kModbusWriteMultiple, address, static_cast<std::uint16_t>(values.size())));
  writer.u8(static_cast<std::uint8_t>(values.size() * 2));
  for (const std::uint16_t value : values) writer.u16_be(value);
  return Request{.reg = number(Register::kToolModbus), .params = writer.take()};
}

Result<std::vector<std::uint16_t>> parse_tool_modbus_read_reply(ByteView data, std::uint8_t slave,
                                                                std::uint16_t count) {
  const std::size_t expected = kReadHeaderBytes + std::size_t{2} * count;
  if (auto head = check_reply_head(data, slave, kModbusReadHolding, expected); !head) return head.error();
  if (data[3] != 2 * count) {
    return make_error(ErrorCode::kInvalidArgument, "tool_modbus_rtu read reply counts " + std::to_string(data[3]) +
                                                       " bytes, expected " + std::to_string(2 * count));
  }
  ByteReader reader(data.subspan(kReadHeaderBytes));
  std::vector<std::uint16_t> values;
  values.reserve(count);
  for (std::uint16_t i = 0; i < count; ++i) values.push_back(reader.u16_be().value_or(0));
  return values;
}

Result<void> parse_tool_modbus_write_reply(ByteView data, std::uint8_t slave, std::uint16_t address,
                                           std::uint16_t count) {
  if (auto head = check_reply_head(data, slave, kModbusWriteMultiple, kWriteEchoBytes); !head) return head.error();
  ByteReader reader(data.subspan(3));
  const std::uint16_t echoed_address = reader.u16_be().value_or(0);
  const std::uint16_t echoed_count = reader.u16_be().value_or(0);
  if (echoed_address != address || echoed_count != count) {
    return make_error(ErrorCode::kInvalidArgument,
                      "tool_modbus_rtu write reply echoes " + std::to_string(echoed_count) + " registers at " +
                          hex16(echoed_address) + ", expected " + std::to_string(count) + " at " + hex16(address));
  }
  return {};
}

Result<ToolModbusRequest> parse_tool_modbus_request(ByteView params) {
  if (params.size() < kRequestHeaderBytes) {
    return size_error("tool_modbus_rtu request", "parameter byte", params.size(), kRequestHeaderBytes, true);
  }
  ByteReader reader(params);
  ToolModbusRequest request;
  request.host_id = reader.u8().value_or(0);
  request.slave = reader.u8().value_or(0);
  request.function = reader.u8().value_or(0);
  request.address = reader.u16_be().value_or(0);
  request.count = reader.u16_be().value_or(0);
  if (request.function == kModbusReadHolding) return request;
  if (request.function != kModbusWriteMultiple) {
    return make_error(ErrorCode::kInvalidArgument, "tool_modbus_rtu function " + std::to_string(request.function) +
                                                       " is not 3 (read) or 16 (write)");
  }
  const std::size_t expected = kRequestHeaderBytes + 1 + std::size_t{2} * request.count;
  if (params.size() < expected || params[kRequestHeaderBytes] != 2 * request.count) {
    return size_error("tool_modbus_rtu write request", "parameter byte", params.size(), expected, false);
  }
  reader.u8();  // the byte count, checked above
  for (std::uint16_t i = 0; i < request.count; ++i) request.values.push_back(reader.u16_be().value_or(0));
  return request;
}

Bytes encode_tool_modbus_read_reply(std::uint8_t slave, std::span<const std::uint16_t> values) {
  ByteWriter writer;
  writer.u8(kToolHostId).u8(slave).u8(kModbusReadHolding).u8(static_cast<std::uint8_t>(values.size() * 2));
  for (const std::uint16_t value : values) writer.u16_be(value);
  return writer.take();
}

Bytes encode_tool_modbus_write_reply(std::uint8_t slave, std::uint16_t address, std::uint16_t count) {
  return modbus_head(slave, kModbusWriteMultiple, address, count);
}

Bytes encode_tool_modbus_exception(std::uint8_t slave, std::uint8_t function, std::uint8_t code) {
  return ByteWriter().u8(kToolHostId).u8(slave).u8(function | kModbusExceptionBit).u8(code).take();
}

Request tool_register_read_request(std::uint8_t id, std::uint16_t address) {
  return Request{.reg = number(Register::kToolRead16), .params = ByteWriter().u8(id).u16_be(address).take()};
}

Result<ToolRegisterAccess> parse_tool_register_access(std::uint8_t reg, ByteView params) {
  const bool write = reg == number(Register::kToolWrite16) || reg == number(Register::kToolWrite32);
  const std::size_t expected = write ? kToolRegisterWriteBytes : kToolRegisterReadBytes;
  if (params.size() < expected) {
    return size_error(register_name(reg) + " request", "parameter byte", params.size(), expected, true);
  }
  ByteReader reader(params);
  ToolRegisterAccess access;
  access.id = reader.u8().value_or(0);
  access.address = reader.u16_be().value_or(0);
  if (write) access.value = read_f32(reader);
  return access;
}

Bytes encode_tool_register_value(std::int32_t value) {
  return ByteWriter().u32_be(static_cast<std::uint32_t>(value)).take();
}

Result<std::int32_t> parse_tool_register_value(ByteView data) {
  if (data.size() < kToolRegisterValueBytes) {
    return size_error("tool register reply", "data byte", data.size(), kToolRegisterValueBytes, true);
  }
  return static_cast<std::int32_t>(ByteReader(data).u32_be().value_or(0));
}

}  // namespace robotd::xarm
