#include "sim/gcode/expression.h"

#include <array>
#include <cmath>
#include <string>

namespace mdhd::gcode {
namespace {

constexpr double kToleranceEqual = 0.0001;  // LinuxCNC's TOLERANCE_EQUAL for EQ / NE

enum class Op {
  kNone,
  kPower,
  kTimes,
  kDivide,
  kMod,
  kPlus,
  kMinus,
  kEq,
  kNe,
  kGt,
  kGe,
  kLt,
  kLe,
  kAnd,
  kOr,
  kXor
};

struct OpName {
  std::string_view text;
  Op op;
};
constexpr std::array<OpName, 14> kNamedOps{{{"**", Op::kPower},
                                            {"*", Op::kTimes},
                                            {"/", Op::kDivide},
                                            {"mod", Op::kMod},
                                            {"+", Op::kPlus},
                                            {"-", Op::kMinus},
                                            {"eq", Op::kEq},
                                            {"ne", Op::kNe},
                                            {"gt", Op::kGt},
                                            {"ge", Op::kGe},
                                            {"lt", Op::kLt},
                                            {"le", Op::kLe},
                                            {"and", Op::kAnd},
                                            {"or", Op::kOr}}};

int precedence(Op op) {
  switch (op) {
    case Op::kPower:
      return 4;
    case Op::kTimes:
    case Op::kDivide:
    case Op::kMod:
      return 3;
    case Op::kPlus:
    case Op::kMinus:
      return 2;
    case Op::kEq:
    case Op::kNe:
    case Op::kGt:
    case Op::kGe:
    case Op::kLt:
    case Op::kLe:
      return 1;
    default:
      return 0;  // AND OR XOR
  }
}

bool isLetter(char c) {
  return c >= 'a' && c <= 'z';
}

// The operator at the cursor and its length; kNone at ']' or end.
std::pair<Op, std::size_t> peekOperator(const Cursor& c) {
  const std::string_view rest = c.rest();
  if (rest.substr(0, 3) == "xor") return {Op::kXor, 3};
  for (const OpName& named : kNamedOps) {
    if (rest.substr(0, named.text.size()) == named.text) return {named.op, named.text.size()};
  }
  return {Op::kNone, 0};
}

// LinuxCNC checks every value it reads for NaN and infinity.
double checkFinite(double value, const Cursor& c, std::size_t at) {
  if (std::isnan(value)) c.failAt(at, "Calculation resulted in 'not a number'");
  if (std::isinf(value)) c.failAt(at, "Calculation resulted in 'infinity'");
  return value;
}

// Trigonometry in degrees, computed in long double as LinuxCNC does (its
// M_PIl makes the argument long double), so results agree to the last bit.
constexpr long double kPi = 3.141592653589793238462643383279502884L;
double sinDegrees(double x) {
  return static_cast<double>(std::sin((x * kPi) / 180.0L));
}
double cosDegrees(double x) {
  return static_cast<double>(std::cos((x * kPi) / 180.0L));
}
double tanDegrees(double x) {
  return static_cast<double>(std::tan((x * kPi) / 180.0L));
}
double toDegrees(double radians) {
  return static_cast<double>((radians * 180.0L) / kPi);
}

// LinuxCNC's ROUND: (int)(x +- 0.5); beyond int range, where that cast is
// undefined, the nearest integer.
double roundLikeLinuxCnc(double x) {
  const double shifted = x + (x < 0.0 ? -0.5 : 0.5);
  if (std::fabs(shifted) < 2147483647.0) return std::trunc(shifted);
  return std::round(x);
}

double apply(Op op, double left, double right, const Cursor& c, std::size_t at) {
  double result = 0.0;
  switch (op) {
    case Op::kPower:
      if (left < 0.0 && std::floor(right) != right) {
        c.failAt(at, "Attempt to raise negative to non-integer power");
      }
      result = std::pow(left, right);
      break;
    case Op::kTimes:
      result = left * right;
      break;
    case Op::kDivide:
      if (right == 0.0) c.failAt(at, "Attempt to divide by zero");
      result = left / right;
      break;
    case Op::kMod:  // by zero gives NaN, reported as LinuxCNC does
      result = std::fmod(left, right);
      if (result < 0.0) result += std::fabs(right);  // LinuxCNC: MOD is never negative
      break;
    case Op::kPlus:
      result = left + right;
      break;
    case Op::kMinus:
      result = left - right;
      break;
    case Op::kEq:
      result = std::fabs(left - right) < kToleranceEqual ? 1.0 : 0.0;
      break;
    case Op::kNe:
      result = std::fabs(left - right) >= kToleranceEqual ? 1.0 : 0.0;
      break;
    case Op::kGt:
      result = left > right ? 1.0 : 0.0;
      break;
    case Op::kGe:  // GE and LE compare exactly, no EQ tolerance (rs274 2.9)
      result = left >= right ? 1.0 : 0.0;
      break;
    case Op::kLt:
      result = left < right ? 1.0 : 0.0;
      break;
    case Op::kLe:
      result = left <= right ? 1.0 : 0.0;
      break;
    case Op::kAnd:
      result = (left != 0.0 && right != 0.0) ? 1.0 : 0.0;
      break;
    case Op::kOr:
      result = (left != 0.0 || right != 0.0) ? 1.0 : 0.0;
      break;
    case Op::kXor:
      result = ((left != 0.0) != (right != 0.0)) ? 1.0 : 0.0;
      break;
    case Op::kNone:
      break;
  }
  return result;
}

// Leaves the depth counter as it found it, also when an error unwinds.
class DepthGuard {
 public:
  explicit DepthGuard(int& depth) : depth_(depth) { ++depth_; }
  ~DepthGuard() { --depth_; }
  DepthGuard(const DepthGuard&) = delete;
  DepthGuard& operator=(const DepthGuard&) = delete;

 private:
  int& depth_;
};

}  // namespace

void ExpressionReader::enter(const Cursor& c) {
  if (depth_ > kMaxDepth) c.fail("Expression nested too deeply (more than 64 levels)");
}

double ExpressionReader::readRealValue(Cursor& c) {
  DepthGuard guard(depth_);
  enter(c);
  const std::size_t start = c.index();
  const char ch = c.peek();
  double value = 0.0;
  if (c.atEnd()) {
    c.fail("No characters found in reading real value");
  } else if (ch == '[') {
    value = readExpression(c);
  } else if (ch == '#') {
    const ParameterRef ref = readParameterRef(c);
    value = parameterValue(ref, c);
  } else if (ch == '-') {
    c.advance();
    value = -readRealValue(c);
  } else if (ch == '+') {
    c.advance();
    value = readRealValue(c);
  } else if (isLetter(ch)) {
    value = readFunction(c);
  } else {
    value = c.readUnsignedNumber();
  }
  return checkFinite(value, c, start);
}

int ExpressionReader::readIntegerValue(Cursor& c) {
  const std::size_t start = c.index();
  const double value = readRealValue(c);
  if (std::fabs(value) > 2e9) c.failAt(start, "Integer value out of range");
  // As LinuxCNC: within 0.0001 of an integer counts as that integer.
  const double below = std::floor(value);
  double result = below;
  if (value - below > 0.9999) {
    result = std::ceil(value);
  } else if (value - below > 0.0001) {
    c.failAt(start, "Non-integer value for integer");
  }
  return static_cast<int>(result);
}

double ExpressionReader::readExpression(Cursor& c) {
  DepthGuard guard(depth_);
  enter(c);
  const std::size_t open = c.index();
  c.advance();  // '['
  const double value = readBinary(c, 0);
  if (c.atEnd()) c.failAt(open, "Unclosed expression (missing ']')");
  c.advance();  // ']'
  return checkFinite(value, c, open);
}

double ExpressionReader::readBinary(Cursor& c, int min_precedence) {
  double left = readRealValue(c);
  for (;;) {
    if (c.atEnd() || c.peek() == ']') return left;
    const auto [op, length] = peekOperator(c);
    if (op == Op::kNone) {
      if (isLetter(c.peek())) {
        c.fail(std::string("Unknown operation name starting with ") +
               static_cast<char>(c.peek() - 'a' + 'A'));
      }
      c.fail("Unknown operation '" + std::string(1, c.peek()) + "' in expression");
    }
    const int p = precedence(op);
    if (p < min_precedence) return left;
    const std::size_t at = c.index();
    c.advance(length);
    // Operators of equal precedence group to the left, as in LinuxCNC.
    const double right = readBinary(c, p + 1);
    left = apply(op, left, right, c, at);
  }
}

double ExpressionReader::readFunction(Cursor& c) {
  const std::size_t start = c.index();
  std::size_t end = start;
  std::string_view rest = c.rest();
  std::size_t n = 0;
  while (n < rest.size() && isLetter(rest[n])) ++n;
  const std::string_view name = rest.substr(0, n);
  end = start + n;
  c.setIndex(end);
  if (c.peek() != '[') {
    static constexpr std::array<std::string_view, 14> kNames{
        "abs", "acos", "asin",  "atan", "cos",  "exp", "fix",
        "fup", "ln",   "round", "sin",  "sqrt", "tan", "exists"};
    for (std::string_view known : kNames) {
      if (name == known) c.fail("Left bracket missing after unary operation name");
    }
    c.failAt(start, "Unknown word where unary operation could be");
  }
  if (name == "exists") return readExists(c);
  const double arg = readExpression(c);
  double result = 0.0;
  if (name == "abs") {
    result = std::fabs(arg);
  } else if (name == "acos") {
    if (arg < -1.0 || arg > 1.0) c.failAt(start, "Argument to ACOS out of range");
    result = toDegrees(std::acos(arg));
  } else if (name == "asin") {
    if (arg < -1.0 || arg > 1.0) c.failAt(start, "Argument to ASIN out of range");
    result = toDegrees(std::asin(arg));
  } else if (name == "atan") {
    if (c.peek() != '/') c.fail("Slash missing after first ATAN argument");
    c.advance();
    if (c.peek() != '[') c.fail("Left bracket missing after slash with ATAN");
    const double x = readExpression(c);
    result = toDegrees(std::atan2(arg, x));
  } else if (name == "cos") {
    result = cosDegrees(arg);
  } else if (name == "exp") {
    result = std::exp(arg);
  } else if (name == "fix") {
    result = std::floor(arg);
  } else if (name == "fup") {
    result = std::ceil(arg);
  } else if (name == "ln") {
    if (arg <= 0.0) c.failAt(start, "Zero or negative argument to LN");
    result = std::log(arg);
  } else if (name == "round") {
    result = roundLikeLinuxCnc(arg);
  } else if (name == "sin") {
    result = sinDegrees(arg);
  } else if (name == "sqrt") {
    if (arg < 0.0) c.failAt(start, "Negative argument to SQRT");
    result = std::sqrt(arg);
  } else if (name == "tan") {
    result = tanDegrees(arg);
  } else {
    c.failAt(start, "Unknown function '" + std::string(name) + "'");
  }
  return result;
}

// EXISTS[#<name>]: 1 if the named parameter is defined. For a numbered one
// LinuxCNC answers whether the number is in range.
double ExpressionReader::readExists(Cursor& c) {
  c.advance();  // '['
  if (c.peek() != '#') c.fail("Expected # reading parameter");
  double result = 0.0;
  if (c.peekAt(1) == '<') {
    const ParameterRef ref = readParameterRef(c);
    result = params_.findNamed(ref.name).has_value() ? 1.0 : 0.0;
  } else {
    c.advance();
    result = ParameterStore::validNumber(readIntegerValue(c)) ? 1.0 : 0.0;
  }
  if (c.peek() != ']') c.fail("Expected ] reading bracketed parameter");
  c.advance();
  return result;
}

ParameterRef ExpressionReader::readParameterRef(Cursor& c) {
  DepthGuard guard(depth_);
  enter(c);
  ParameterRef ref;
  ref.index = c.index();
  c.advance();  // '#'
  if (c.peek() == '<') {
    const std::string_view rest = c.rest();
    const std::size_t close = rest.find('>');
    if (close == std::string_view::npos) c.fail("Named parameter not terminated");
    if (close == 1) c.fail("Named parameter has no name");
    ref.named = true;
    ref.name = rest.substr(1, close - 1);
    c.advance(close + 1);
    return ref;
  }
  const std::size_t at = c.index();
  ref.number = readIntegerValue(c);
  if (!ParameterStore::validNumber(ref.number)) c.failAt(at, "Parameter number out of range");
  return ref;
}

double ExpressionReader::parameterValue(const ParameterRef& ref, const Cursor& c) const {
  if (!ref.named) return params_.get(ref.number);
  const auto value = params_.findNamed(ref.name);
  if (!value) c.failAt(ref.index, "Named parameter #<" + std::string(ref.name) + "> not defined");
  return *value;
}

}  // namespace mdhd::gcode
