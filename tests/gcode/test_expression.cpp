#include "sim/gcode/expression.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/gcode/test_reader_helpers.h"

namespace mdhd::gcode {
namespace {

using testing::readAll;
using testing::readError;

// The value of X after reading "X<text>".
double x(const std::string& text) {
  const auto blocks = readAll("X" + text + "\n");
  EXPECT_EQ(blocks.size(), 1u);
  return blocks.empty() ? NAN : blocks[0].words.at(0).value;
}

TEST(Expression, Arithmetic) {
  EXPECT_EQ(x("[2**3]"), 8.0);
  EXPECT_EQ(x("[7 MOD 4]"), 3.0);
  EXPECT_EQ(x("[-7 MOD 4]"), 1.0);  // LinuxCNC: MOD is never negative
  EXPECT_EQ(x("[1 + 2 * 3]"), 7.0);
  EXPECT_EQ(x("[[1 + 2] * 3]"), 9.0);
  EXPECT_EQ(x("[10 / 4]"), 2.5);
  EXPECT_EQ(x("[10 - 4 - 3]"), 3.0);    // left to right
  EXPECT_EQ(x("[2 ** 3 ** 2]"), 64.0);  // left to right, as LinuxCNC
  EXPECT_EQ(x("[2 * 3 ** 2]"), 18.0);   // ** binds tighter
  EXPECT_EQ(x("[-2 ** 2]"), 4.0);       // unary minus binds to the value
  EXPECT_EQ(x("[3 - -2]"), 5.0);
  EXPECT_EQ(x("[+2]"), 2.0);
  EXPECT_EQ(x("-[1+1]"), -2.0);
  EXPECT_EQ(x("-.5"), -0.5);
  EXPECT_EQ(x("+2"), 2.0);
  EXPECT_EQ(x("[ 1 . 5 * 2 ]"), 3.0);
}

TEST(Expression, ComparisonsAndLogic) {
  EXPECT_EQ(x("[1 LT 2]"), 1.0);
  EXPECT_EQ(x("[2 LT 2]"), 0.0);
  EXPECT_EQ(x("[2 LE 2]"), 1.0);
  // EQ / NE hold within 0.0001, LE / GE do not: rs274 2.9 gives 0 for both of these
  // (mdhd gave 1, so a `while [#1 LE 10]` loop on a sum of 0.1 steps ran once more).
  EXPECT_EQ(x("[2.00005 LE 2]"), 0.0);
  EXPECT_EQ(x("[2 GE 2.00005]"), 0.0);
  EXPECT_EQ(x("[2.00005 GE 2]"), 1.0);
  EXPECT_EQ(x("[2 EQ 2.00005]"), 1.0);
  EXPECT_EQ(x("[2 NE 2.00005]"), 0.0);
  EXPECT_EQ(x("[2.001 LE 2]"), 0.0);
  EXPECT_EQ(x("[3 GT 2]"), 1.0);
  EXPECT_EQ(x("[2 GE 3]"), 0.0);
  EXPECT_EQ(x("[2 EQ 2.00001]"), 1.0);  // LinuxCNC compares EQ/NE within 0.0001
  EXPECT_EQ(x("[2 NE 2.001]"), 1.0);
  EXPECT_EQ(x("[1 AND 0]"), 0.0);
  EXPECT_EQ(x("[1 OR 0]"), 1.0);
  EXPECT_EQ(x("[1 XOR 1]"), 0.0);
  EXPECT_EQ(x("[1 XOR 0]"), 1.0);
  // Precedence: + before comparison before logic.
  EXPECT_EQ(x("[1 + 1 EQ 2 AND 3 GT 2]"), 1.0);
  EXPECT_EQ(x("[1 lt 2 eq 1]"), 1.0);
}

TEST(Expression, Functions) {
  EXPECT_EQ(x("[ATAN[1]/[1]]"), 45.0);
  EXPECT_EQ(x("[ATAN[-1]/[-1]]"), -135.0);
  EXPECT_EQ(x("[ABS[-2.5]]"), 2.5);
  EXPECT_EQ(x("[SQRT[16]]"), 4.0);
  EXPECT_EQ(x("[EXP[0]]"), 1.0);
  EXPECT_EQ(x("[LN[1]]"), 0.0);
  EXPECT_EQ(x("[FIX[2.7]]"), 2.0);
  EXPECT_EQ(x("[FIX[-2.7]]"), -3.0);  // FIX rounds down
  EXPECT_EQ(x("[FUP[2.2]]"), 3.0);
  EXPECT_EQ(x("[FUP[-2.2]]"), -2.0);  // FUP rounds up
  EXPECT_EQ(x("[ROUND[2.5]]"), 3.0);
  EXPECT_EQ(x("[ROUND[-2.5]]"), -3.0);  // half away from zero
  EXPECT_EQ(x("[ROUND[-2.4]]"), -2.0);
  EXPECT_EQ(x("[ROUND[0.49999999999999994]]"), 1.0);     // LinuxCNC adds 0.5, then truncates
  EXPECT_EQ(x("[ROUND[1000000000000.5]]"), 1e12 + 1.0);  // beyond int: no overflow
  EXPECT_EQ(x("[SIN[30]]"), 0.5);                        // in long double as LinuxCNC: exactly 0.5
  constexpr long double kPi = 3.141592653589793238462643383279502884L;
  EXPECT_EQ(x("[COS[90]]"), static_cast<double>(std::cos((90.0L * kPi) / 180.0L)));
  EXPECT_NEAR(x("[COS[60]]"), 0.5, 1e-15);
  EXPECT_NEAR(x("[TAN[45]]"), 1.0, 1e-15);
  EXPECT_NEAR(x("[ASIN[0.5]]"), 30.0, 1e-13);
  EXPECT_NEAR(x("[ACOS[0.5]]"), 60.0, 1e-13);
  EXPECT_EQ(x("sqrt[9]"), 3.0);  // a function right after the letter
  // The sum of 15_oword_params_expr.ngc line 5: 0.5+0.5+4+1+2+3+3.
  EXPECT_NEAR(x("[SIN[30] + COS[60] + SQRT[16] + ABS[-1] + FIX[2.7] + FUP[2.2] + ROUND[2.5]]"),
              14.0, 1e-12);
}

TEST(Expression, Exists) {
  const auto blocks =
      readAll("#<a> = 1\nX[EXISTS[#<a>]] Y[EXISTS[#<b>]] Z[EXISTS[#5601]] A[EXISTS[#5602]]\n");
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_EQ(blocks[0].words[0].value, 1.0);
  EXPECT_EQ(blocks[0].words[1].value, 0.0);
  EXPECT_EQ(blocks[0].words[2].value, 1.0);  // numbered: is the number in range
  EXPECT_EQ(blocks[0].words[3].value, 0.0);
  EXPECT_STREQ(readError("X[EXISTS[1]]").what(), "Expected # reading parameter");
  EXPECT_STREQ(readError("X[EXISTS[#<a> + 1]]").what(), "Expected ] reading bracketed parameter");
}

struct ErrorCase {
  const char* program;
  const char* message;
  int column;
};

TEST(Expression, ErrorsNameWhatAndWhere) {
  const ErrorCase cases[] = {
      {"G1 X[1/0]", "Attempt to divide by zero", 7},
      {"G1 X[1 MOD 0]", "Calculation resulted in 'not a number'", 5},
      {"G1 X[SQRT[-1]]", "Negative argument to SQRT", 6},
      {"G1 X[LN[0]]", "Zero or negative argument to LN", 6},
      {"G1 X[ACOS[2]]", "Argument to ACOS out of range", 6},
      {"G1 X[ASIN[-2]]", "Argument to ASIN out of range", 6},
      {"G1 X[[-8]**0.5]", "Attempt to raise negative to non-integer power", 10},
      {"G1 X[FOO[1]]", "Unknown function 'foo'", 6},
      {"G1 X[1 + 2", "Unclosed expression (missing ']')", 5},
      {"G1 X[ATAN[1]]", "Slash missing after first ATAN argument", 13},
      {"G1 X[ATAN[1]/2]", "Left bracket missing after slash with ATAN", 14},
      {"G1 X[1 FOO 2]", "Unknown operation name starting with F", 8},
      {"G1 X[1 ! 2]", "Unknown operation '!' in expression", 8},
      {"G1 X[SIN 30]", "Left bracket missing after unary operation name", 10},
      {"G1 Xy1", "Unknown word where unary operation could be", 5},
      {"G1 X[10**400]", "Calculation resulted in 'infinity'", 5},
      {"G1 X[EXP[1000]]", "Calculation resulted in 'infinity'", 6},
      {"G1 X1.2.3", "bad number format (trailing characters) parsing '1.2.3'", 5},
      {"G1 X#<nope>", "Named parameter #<nope> not defined", 5},
      {"G1 X#0", "Parameter number out of range", 6},
      {"G1 X#5602", "Parameter number out of range", 6},  // LinuxCNC: #1..#5601
      {"G1 X#1.5", "Non-integer value for integer", 6},
      {"G1 X", "No characters found in reading real value", 5},
      {"G1 X[]", "bad number format (conversion failed) parsing ''", 6},
      {"G1 X.", "bad number format (conversion failed) parsing '.'", 5},
  };
  for (const ErrorCase& c : cases) {
    const GcodeError e = readError(std::string("\n") + c.program + "\n");
    EXPECT_EQ(std::string(e.what()), c.message) << c.program;
    EXPECT_EQ(e.line(), 2) << c.program;
    EXPECT_EQ(e.column(), c.column) << c.program;
  }
}

TEST(Expression, DeepNestingIsAnErrorNotACrash) {
  const std::string deep = "X" + std::string(5000, '[') + "1" + std::string(5000, ']');
  const GcodeError e = readError(deep);
  EXPECT_STREQ(e.what(), "Expression nested too deeply (more than 64 levels)");
  const std::string minus = "X" + std::string(5000, '-') + "1";
  EXPECT_STREQ(readError(minus).what(), "Expression nested too deeply (more than 64 levels)");
  const std::string hashes = "X" + std::string(5000, '#') + "1";
  EXPECT_STREQ(readError(hashes).what(), "Expression nested too deeply (more than 64 levels)");
}

TEST(Expression, ModeratelyDeepNestingIsFine) {
  EXPECT_EQ(x(std::string(30, '[') + "2" + std::string(30, ']')), 2.0);
}

}  // namespace
}  // namespace mdhd::gcode
