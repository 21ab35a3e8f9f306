#pragma once
// The Modbus TCP register map of live shadowing (service.md, "Live shadowing over
// Modbus TCP") as plain data, and the pure functions around it: registers as read
// (uint16 words) <-> values, validation against a machine, and the plan of reads
// that fetches every mapped register in the fewest requests.
//
// Word orders are named as libmodbus names them: the 32-bit value's bytes A (most
// significant) .. D as they appear over the wire, register by register:
//   abcd: [AB][CD]   badc: [BA][DC]   cdab: [CD][AB]   dcba: [DC][BA]
// e.g. 1.5f (0x3FC00000) is 0x3FC0 0x0000 in abcd and 0x0000 0x3FC0 in cdab.
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/gcode/motion.h"
#include "sim/kinematics/machine.h"

namespace mdhd::protocol {

enum class RegisterTable { kHolding, kInput };  // function 3 / function 4
enum class RegisterType { kFloat32, kInt32, kUint32, kInt16, kUint16 };
enum class WordOrder { kAbcd, kBadc, kCdab, kDcba };

// One value in the register table.
struct RegisterField {
  int address = 0;  // 0-based register address of the first word
  RegisterType type = RegisterType::kFloat32;
  WordOrder word_order = WordOrder::kAbcd;  // 32-bit types only
  double scale = 1.0;                       // value = raw * scale
};

struct JointRegister {
  std::string name;  // the machine joint's name ("X", "A", ...)
  gcode::Axis axis = gcode::kX;
  RegisterField field;
};

struct FeedHold {
  int coil = 0;
  bool enabled = false;  // writing to a controller is the user's explicit choice
};

struct ModbusMap {
  std::string host;
  int port = 502;
  int unit_id = 1;
  double poll_hz = 50.0;
  int timeout_ms = 200;
  RegisterTable table = RegisterTable::kHolding;
  std::vector<JointRegister> joints;
  std::optional<RegisterField> tool;
  std::optional<RegisterField> spindle_on;
  std::optional<RegisterField> line;
  FeedHold feed_hold;
};

// Accepted ranges (documented in docs/modbus.md).
inline constexpr double kMinPollHz = 0.1;
inline constexpr double kMaxPollHz = 1000.0;
inline constexpr int kMinTimeoutMs = 1;
inline constexpr int kMaxTimeoutMs = 60000;
inline constexpr int kMaxRegistersPerRead = 125;    // Modbus function 3/4 limit
inline constexpr std::size_t kMaxHostLength = 253;  // a DNS name's limit

// A decoded value that cannot be a machine value (NaN, infinity), or a value that
// cannot be encoded in its register type.
class RegisterValueError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Registers a type occupies: 1 for 16-bit types, 2 for 32-bit types.
int registerCount(RegisterType type);

// The 32-bit pattern 0xAABBCCDD from the two registers as read, per word order.
std::uint32_t joinWords(std::uint16_t first, std::uint16_t second, WordOrder order);
// Its inverse: the two registers to write for a 32-bit pattern.
void splitWords(std::uint32_t bits, WordOrder order, std::uint16_t& first, std::uint16_t& second);

// The raw value (before scale) of a field from its registers (words.size() must be
// registerCount). Signed types are sign-extended. Float NaN/inf is returned as is.
double rawValue(const RegisterField& field, std::span<const std::uint16_t> words);

// raw * scale. Throws RegisterValueError naming `what` when the result is not finite.
double decodeField(const RegisterField& field, std::span<const std::uint16_t> words,
                   const std::string& what);

// The registers for value / scale: rounded to the nearest integer for integer types.
// Throws RegisterValueError when it is not finite or out of the type's range.
void encodeField(const RegisterField& field, double value, std::span<std::uint16_t> words,
                 const std::string& what);

// One problem of a map: `field` is the path below the modbus block in the
// document's spelling ("joints.X.address", "poll_hz"), `message` what is wrong.
struct ModbusMapIssue {
  std::string field;
  std::string message;
};

// Every problem: ranges of the settings, addresses (0..65535, the second word of
// 32-bit types included), overlapping fields, zero or non-finite scales and, with a
// machine, joint names it lacks and joints of the machine that have no register.
std::vector<ModbusMapIssue> validateModbusMap(const ModbusMap& map,
                                              const kin::Machine* machine = nullptr);

// One read request: `count` registers from `start`.
struct ReadBlock {
  int start = 0;
  int count = 0;
};

// The fewest reads of at most kMaxRegistersPerRead registers that cover every
// field, in address order; a compact map is one read of min..max address.
std::vector<ReadBlock> planReads(const ModbusMap& map);

// What one poll says about the machine.
struct ModbusSample {
  gcode::AxisValues joints{};  // by axis letter; mapped joints only
  unsigned joint_mask = 0;     // bit per gcode::Axis present in `joints`
  std::optional<int> tool;
  std::optional<bool> spindle_on;
  std::optional<std::int64_t> line;
};

// Decodes a poll: `words[i]` holds the registers read for `blocks[i]`. Throws
// RegisterValueError naming the field for NaN/inf or a tool/line that is not an
// integer in range.
ModbusSample decodeSample(const ModbusMap& map, const std::vector<ReadBlock>& blocks,
                          const std::vector<std::vector<std::uint16_t>>& words);

// Writes a sample into a register image indexed by address (the simulated
// controller's table). The image must cover every field.
void encodeSample(const ModbusMap& map, const ModbusSample& sample, std::span<std::uint16_t> image);

// The registers a map needs from address 0: one past its highest register.
int registerSpan(const ModbusMap& map);

// The default map of a machine (docs/modbus.md): its joints in order as float32
// abcd from address 0, two registers each, then tool uint16, spindle_on uint16,
// line uint32; feed hold on coil 0 (disabled); host 127.0.0.1.
ModbusMap defaultModbusMap(const kin::Machine& machine);

const char* registerTypeName(RegisterType type);
const char* wordOrderName(WordOrder order);
const char* registerTableName(RegisterTable table);

}  // namespace mdhd::protocol
