// A whole poll: the map's fields decoded from (or encoded into) registers.
#include <cmath>
#include <limits>

#include "protocol/modbus_map.h"

namespace mdhd::protocol {
namespace {

// The registers of `field` inside the block that holds it.
std::span<const std::uint16_t> fieldWords(const RegisterField& field,
                                          const std::vector<ReadBlock>& blocks,
                                          const std::vector<std::vector<std::uint16_t>>& words,
                                          const std::string& what) {
  const int n = registerCount(field.type);
  for (std::size_t i = 0; i < blocks.size() && i < words.size(); ++i) {
    const ReadBlock& b = blocks[i];
    if (field.address >= b.start && field.address + n <= b.start + b.count &&
        words[i].size() >= static_cast<std::size_t>(b.count)) {
      return {words[i].data() + (field.address - b.start), static_cast<std::size_t>(n)};
    }
  }
  throw RegisterValueError(what + ": register " + std::to_string(field.address) + " was not read");
}

std::int64_t wholeNumber(double v, double max, const std::string& what) {
  if (v != std::floor(v) || v < 0.0 || v > max) {
    throw RegisterValueError(what + ": the controller sent " + std::to_string(v) +
                             ", not a whole number in 0.." + std::to_string(std::int64_t(max)));
  }
  return static_cast<std::int64_t>(v);
}

void encodeAt(const RegisterField& field, double value, std::span<std::uint16_t> image,
              const std::string& what) {
  const auto n = static_cast<std::size_t>(registerCount(field.type));
  const auto at = static_cast<std::size_t>(field.address);
  if (field.address < 0 || at + n > image.size()) {
    throw RegisterValueError(what + ": register " + std::to_string(field.address) +
                             " is outside the register table");
  }
  encodeField(field, value, image.subspan(at, n), what);
}

}  // namespace

ModbusSample decodeSample(const ModbusMap& map, const std::vector<ReadBlock>& blocks,
                          const std::vector<std::vector<std::uint16_t>>& words) {
  ModbusSample s;
  for (const JointRegister& j : map.joints) {
    const std::string what = "joints." + j.name;
    s.joints[j.axis] = decodeField(j.field, fieldWords(j.field, blocks, words, what), what);
    s.joint_mask |= 1u << j.axis;
  }
  if (map.tool) {
    const double v = decodeField(*map.tool, fieldWords(*map.tool, blocks, words, "tool"), "tool");
    s.tool = static_cast<int>(wholeNumber(v, std::numeric_limits<int>::max(), "tool"));
  }
  if (map.spindle_on) {
    const auto w = fieldWords(*map.spindle_on, blocks, words, "spindle_on");
    s.spindle_on = decodeField(*map.spindle_on, w, "spindle_on") != 0.0;
  }
  if (map.line) {
    const double v = decodeField(*map.line, fieldWords(*map.line, blocks, words, "line"), "line");
    s.line = wholeNumber(v, 4294967295.0, "line");
  }
  return s;
}

void encodeSample(const ModbusMap& map, const ModbusSample& sample,
                  std::span<std::uint16_t> image) {
  for (const JointRegister& j : map.joints) {
    encodeAt(j.field, sample.joints[j.axis], image, "joints." + j.name);
  }
  if (map.tool) encodeAt(*map.tool, sample.tool.value_or(0), image, "tool");
  if (map.spindle_on) {
    encodeAt(*map.spindle_on, sample.spindle_on.value_or(false) ? 1.0 : 0.0, image, "spindle_on");
  }
  if (map.line) encodeAt(*map.line, static_cast<double>(sample.line.value_or(0)), image, "line");
}

int registerSpan(const ModbusMap& map) {
  int span = 0;
  auto cover = [&span](const RegisterField& f) {
    span = std::max(span, f.address + registerCount(f.type));
  };
  for (const JointRegister& j : map.joints) cover(j.field);
  if (map.tool) cover(*map.tool);
  if (map.spindle_on) cover(*map.spindle_on);
  if (map.line) cover(*map.line);
  return span;
}

ModbusMap defaultModbusMap(const kin::Machine& machine) {
  ModbusMap map;
  map.host = "127.0.0.1";
  int address = 0;
  for (const kin::Joint& joint : machine.joints) {
    const auto axis = kin::axisOfName(joint.name);
    if (!axis) continue;  // validateMachine refuses such names; skip rather than guess
    map.joints.push_back({joint.name, *axis, {address, RegisterType::kFloat32}});
    address += 2;
  }
  map.tool = RegisterField{address, RegisterType::kUint16};
  map.spindle_on = RegisterField{address + 1, RegisterType::kUint16};
  map.line = RegisterField{address + 2, RegisterType::kUint32};
  return map;
}

}  // namespace mdhd::protocol
