// Register codec: words <-> values, per type, word order and scale.
#include "protocol/modbus_map.h"

#include <bit>
#include <cmath>
#include <limits>

namespace mdhd::protocol {
namespace {

std::uint16_t swapBytes(std::uint16_t w) {
  return static_cast<std::uint16_t>((w << 8) | (w >> 8));
}

bool isInteger(RegisterType t) {
  return t != RegisterType::kFloat32;
}

// The range of raw values a type holds.
void typeRange(RegisterType t, double& lo, double& hi) {
  switch (t) {
    case RegisterType::kInt16:
      lo = -32768.0, hi = 32767.0;
      return;
    case RegisterType::kUint16:
      lo = 0.0, hi = 65535.0;
      return;
    case RegisterType::kInt32:
      lo = -2147483648.0, hi = 2147483647.0;
      return;
    case RegisterType::kUint32:
      lo = 0.0, hi = 4294967295.0;
      return;
    case RegisterType::kFloat32:
      lo = -static_cast<double>(std::numeric_limits<float>::max());
      hi = static_cast<double>(std::numeric_limits<float>::max());
      return;
  }
}

}  // namespace

int registerCount(RegisterType type) {
  return type == RegisterType::kInt16 || type == RegisterType::kUint16 ? 1 : 2;
}

std::uint32_t joinWords(std::uint16_t first, std::uint16_t second, WordOrder order) {
  std::uint16_t high = first;  // AB
  std::uint16_t low = second;  // CD
  switch (order) {
    case WordOrder::kAbcd:
      break;
    case WordOrder::kBadc:
      high = swapBytes(first), low = swapBytes(second);
      break;
    case WordOrder::kCdab:
      high = second, low = first;
      break;
    case WordOrder::kDcba:
      high = swapBytes(second), low = swapBytes(first);
      break;
  }
  return (static_cast<std::uint32_t>(high) << 16) | low;
}

void splitWords(std::uint32_t bits, WordOrder order, std::uint16_t& first, std::uint16_t& second) {
  const auto high = static_cast<std::uint16_t>(bits >> 16);
  const auto low = static_cast<std::uint16_t>(bits & 0xFFFFu);
  switch (order) {
    case WordOrder::kAbcd:
      first = high, second = low;
      return;
    case WordOrder::kBadc:
      first = swapBytes(high), second = swapBytes(low);
      return;
    case WordOrder::kCdab:
      first = low, second = high;
      return;
    case WordOrder::kDcba:
      first = swapBytes(low), second = swapBytes(high);
      return;
  }
}

double rawValue(const RegisterField& field, std::span<const std::uint16_t> words) {
  switch (field.type) {
    case RegisterType::kUint16:
      return words[0];
    case RegisterType::kInt16:
      return static_cast<std::int16_t>(words[0]);
    default:
      break;
  }
  const std::uint32_t bits = joinWords(words[0], words[1], field.word_order);
  switch (field.type) {
    case RegisterType::kUint32:
      return bits;
    case RegisterType::kInt32:
      return static_cast<std::int32_t>(bits);
    default:
      return std::bit_cast<float>(bits);
  }
}

double decodeField(const RegisterField& field, std::span<const std::uint16_t> words,
                   const std::string& what) {
  const double raw = rawValue(field, words);
  if (std::isnan(raw)) throw RegisterValueError(what + ": the controller sent NaN");
  const double v = raw * field.scale;
  if (!std::isfinite(v)) {
    throw RegisterValueError(what + ": the controller sent " + (v > 0 ? "+" : "-") + "infinity");
  }
  return v;
}

void encodeField(const RegisterField& field, double value, std::span<std::uint16_t> words,
                 const std::string& what) {
  double raw = value / field.scale;
  if (!std::isfinite(raw)) throw RegisterValueError(what + ": cannot encode a non-finite value");
  if (isInteger(field.type)) raw = std::round(raw);  // half away from zero
  double lo = 0.0;
  double hi = 0.0;
  typeRange(field.type, lo, hi);
  if (raw < lo || raw > hi) {
    throw RegisterValueError(what + ": " + std::to_string(value) + " does not fit in a " +
                             registerTypeName(field.type));
  }
  std::uint32_t bits = 0;
  switch (field.type) {
    case RegisterType::kUint16:
      words[0] = static_cast<std::uint16_t>(raw);
      return;
    case RegisterType::kInt16:
      words[0] = static_cast<std::uint16_t>(static_cast<std::int16_t>(raw));
      return;
    case RegisterType::kUint32:
      bits = static_cast<std::uint32_t>(raw);
      break;
    case RegisterType::kInt32:
      bits = static_cast<std::uint32_t>(static_cast<std::int32_t>(raw));
      break;
    case RegisterType::kFloat32:
      bits = std::bit_cast<std::uint32_t>(static_cast<float>(raw));
      break;
  }
  splitWords(bits, field.word_order, words[0], words[1]);
}

const char* registerTypeName(RegisterType type) {
  switch (type) {
    case RegisterType::kFloat32:
      return "float32";
    case RegisterType::kInt32:
      return "int32";
    case RegisterType::kUint32:
      return "uint32";
    case RegisterType::kInt16:
      return "int16";
    case RegisterType::kUint16:
      return "uint16";
  }
  return "?";
}

const char* wordOrderName(WordOrder order) {
  switch (order) {
    case WordOrder::kAbcd:
      return "abcd";
    case WordOrder::kBadc:
      return "badc";
    case WordOrder::kCdab:
      return "cdab";
    case WordOrder::kDcba:
      return "dcba";
  }
  return "?";
}

const char* registerTableName(RegisterTable table) {
  return table == RegisterTable::kHolding ? "holding" : "input";
}

}  // namespace mdhd::protocol
