#pragma once
// The `modbus` block of a shadow request (service.md) <-> protocol::ModbusMap.
// Strict: types, ranges, unknown fields, overlapping registers and (given the
// machine) joint names are errors, each a FieldError naming the field's path
// ("modbus.joints.X.word_order").
#include <string>

#include <nlohmann/json.hpp>

#include "protocol/json_fields.h"
#include "protocol/modbus_map.h"

namespace mdhd::protocol {

// Reads and validates a map; `path` is where the block sits in the document.
// Required: host, joints (each with address and type); the rest has the defaults
// of docs/modbus.md. With `machine`, joint names must be exactly its joints.
ModbusMap modbusMapFromJson(const nlohmann::json& j, const std::string& path = "modbus",
                            const kin::Machine* machine = nullptr);

// The block as the contract writes it (every field, defaults included).
nlohmann::json modbusMapToJson(const ModbusMap& map);

}  // namespace mdhd::protocol
