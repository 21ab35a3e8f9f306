// libFuzzer target for the `modbus` block of a shadow (service.md): any bytes either
// fail (not JSON, or a FieldError naming the field) or give a map that round-trips:
// what the codec writes, it reads back to the same block.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>

#include "fuzz/json_input.h"
#include "protocol/job_json.h"
#include "protocol/modbus_map_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace mdhd;
  const std::optional<nlohmann::json> input = fuzz::jsonInput(data, size);
  if (!input) return 0;
  const nlohmann::json& doc = *input;
  protocol::ModbusMap map;
  try {
    map = protocol::modbusMapFromJson(doc);
  } catch (const protocol::FieldError&) {
    return 0;
  }
  const nlohmann::json written = protocol::modbusMapToJson(map);
  if (protocol::modbusMapToJson(protocol::modbusMapFromJson(written)) != written) std::abort();
  return 0;
}
