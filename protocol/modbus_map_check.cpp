// Validation of a register map and the plan of reads for one poll.
#include <algorithm>
#include <cmath>

#include "protocol/modbus_map.h"

namespace mdhd::protocol {
namespace {

struct PlacedField {
  std::string path;  // "joints.X", "tool", ...
  const RegisterField* field;
};

std::vector<PlacedField> placedFields(const ModbusMap& map) {
  std::vector<PlacedField> out;
  for (const JointRegister& j : map.joints) out.push_back({"joints." + j.name, &j.field});
  if (map.tool) out.push_back({"tool", &*map.tool});
  if (map.spindle_on) out.push_back({"spindle_on", &*map.spindle_on});
  if (map.line) out.push_back({"line", &*map.line});
  return out;
}

std::string registers(const RegisterField& f) {
  const int n = registerCount(f.type);
  const std::string first = std::to_string(f.address);
  return n == 1 ? "register " + first
                : "registers " + first + ".." + std::to_string(f.address + n - 1);
}

void checkSettings(const ModbusMap& map, std::vector<ModbusMapIssue>& issues) {
  if (map.host.empty()) {
    issues.push_back({"host", "must name the controller (not empty)"});
  } else if (map.host.size() > kMaxHostLength) {
    issues.push_back({"host", "is " + std::to_string(map.host.size()) +
                                  " characters long: a host name or address has at most " +
                                  std::to_string(kMaxHostLength)});
  } else if (std::any_of(map.host.begin(), map.host.end(), [](char c) {
               const auto u = static_cast<unsigned char>(c);
               return u <= 0x20 || u == 0x7F;
             })) {
    issues.push_back({"host", "must be a host name or address: no spaces or control characters"});
  }
  if (map.port < 1 || map.port > 65535) issues.push_back({"port", "must be in 1..65535"});
  if (map.unit_id < 0 || map.unit_id > 255) issues.push_back({"unit_id", "must be in 0..255"});
  if (!(map.poll_hz >= kMinPollHz && map.poll_hz <= kMaxPollHz)) {
    issues.push_back({"poll_hz", "must be in 0.1..1000 (polls per second)"});
  }
  if (map.timeout_ms < kMinTimeoutMs || map.timeout_ms > kMaxTimeoutMs) {
    issues.push_back({"timeout_ms", "must be in 1..60000"});
  }
  if (map.feed_hold.coil < 0 || map.feed_hold.coil > 65535) {
    issues.push_back({"feed_hold.coil", "must be in 0..65535"});
  }
}

void checkFields(const std::vector<PlacedField>& fields, std::vector<ModbusMapIssue>& issues) {
  for (const PlacedField& p : fields) {
    const RegisterField& f = *p.field;
    const int last = f.address + registerCount(f.type) - 1;
    if (f.address < 0 || last > 65535) {
      issues.push_back({p.path + ".address", registers(f) + " (a " + registerTypeName(f.type) +
                                                 ") is outside 0..65535"});
    }
    if (!std::isfinite(f.scale) || f.scale == 0.0) {
      issues.push_back({p.path + ".scale", "must be a finite number other than 0"});
    }
  }
  std::vector<const PlacedField*> sorted;
  for (const PlacedField& p : fields) sorted.push_back(&p);
  std::stable_sort(sorted.begin(), sorted.end(), [](const PlacedField* a, const PlacedField* b) {
    return a->field->address < b->field->address;
  });
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    const RegisterField& prev = *sorted[i - 1]->field;
    const RegisterField& cur = *sorted[i]->field;
    if (cur.address < prev.address + registerCount(prev.type)) {
      issues.push_back({sorted[i]->path + ".address",
                        registers(cur) +
                            (registerCount(cur.type) == 1 ? " overlaps " : " overlap ") +
                            sorted[i - 1]->path + " (" + registers(prev) + ")"});
    }
  }
}

void checkJoints(const ModbusMap& map, const kin::Machine* machine,
                 std::vector<ModbusMapIssue>& issues) {
  if (map.joints.empty()) issues.push_back({"joints", "must map at least one joint"});
  unsigned seen = 0;
  for (const JointRegister& j : map.joints) {
    const auto axis = kin::axisOfName(j.name);
    if (!axis || *axis != j.axis) {
      issues.push_back({"joints." + j.name, "is not a joint name (X Y Z A B C U V W)"});
      continue;
    }
    if (seen & (1u << j.axis)) issues.push_back({"joints." + j.name, "is mapped twice"});
    seen |= 1u << j.axis;
    if (machine != nullptr && kin::jointIndex(*machine, j.axis) < 0) {
      issues.push_back({"joints." + j.name, "the machine has no joint " + j.name + " (it has " +
                                                kin::axisLetterString(*machine) + ")"});
    }
  }
  if (machine == nullptr) return;
  for (const kin::Joint& joint : machine->joints) {
    const auto axis = kin::axisOfName(joint.name);
    if (axis && !(seen & (1u << *axis))) {
      issues.push_back({"joints", "the machine's joint " + joint.name +
                                      " has no register (every joint must be read for a pose)"});
    }
  }
}

}  // namespace

std::vector<ModbusMapIssue> validateModbusMap(const ModbusMap& map, const kin::Machine* machine) {
  std::vector<ModbusMapIssue> issues;
  checkSettings(map, issues);
  checkJoints(map, machine, issues);
  checkFields(placedFields(map), issues);
  return issues;
}

std::vector<ReadBlock> planReads(const ModbusMap& map) {
  std::vector<std::pair<int, int>> spans;  // [first, one past last)
  for (const PlacedField& p : placedFields(map)) {
    spans.emplace_back(p.field->address, p.field->address + registerCount(p.field->type));
  }
  std::sort(spans.begin(), spans.end());
  // Greedy from the lowest uncovered field: each read reaches as far as the limit
  // allows, which gives the fewest reads for fields on a line.
  std::vector<ReadBlock> blocks;
  int start = 0;
  int end = 0;
  for (const auto& [first, past] : spans) {
    if (!blocks.empty() && past - start <= kMaxRegistersPerRead) {
      end = std::max(end, past);
      blocks.back().count = end - start;
      continue;
    }
    start = first;
    end = past;
    blocks.push_back({start, end - start});
  }
  return blocks;
}

}  // namespace mdhd::protocol
