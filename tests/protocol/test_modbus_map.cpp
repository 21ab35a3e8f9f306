// Register codec, validation and read plans of the Modbus map, value by value
// against register words written out by hand.
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <modbus/modbus.h>

#include "protocol/modbus_map.h"
#include "sim/kinematics/presets.h"

namespace mdhd::protocol {
namespace {

using ::testing::HasSubstr;
using Words = std::vector<std::uint16_t>;

RegisterField field(RegisterType type, WordOrder order = WordOrder::kAbcd, double scale = 1.0) {
  return {0, type, order, scale};
}

double raw(RegisterType type, WordOrder order, Words words) {
  return rawValue(field(type, order), words);
}

struct OrderCase {
  WordOrder order;
  Words words;
};

// 3.14f is 0x4048F5C3: bytes A=40 B=48 C=F5 D=C3, all different, so every order is
// distinguishable.
TEST(ModbusCodec, Float32EveryWordOrder) {
  const OrderCase cases[] = {{WordOrder::kAbcd, {0x4048, 0xF5C3}},
                             {WordOrder::kBadc, {0x4840, 0xC3F5}},
                             {WordOrder::kCdab, {0xF5C3, 0x4048}},
                             {WordOrder::kDcba, {0xC3F5, 0x4840}}};
  for (const auto& c : cases) {
    EXPECT_EQ(raw(RegisterType::kFloat32, c.order, c.words), static_cast<double>(3.14f))
        << wordOrderName(c.order);
  }
}

TEST(ModbusCodec, OnePointFiveAsTheBriefWritesIt) {
  EXPECT_EQ(raw(RegisterType::kFloat32, WordOrder::kAbcd, {0x3FC0, 0x0000}), 1.5);
  EXPECT_EQ(raw(RegisterType::kFloat32, WordOrder::kCdab, {0x0000, 0x3FC0}), 1.5);
  EXPECT_EQ(raw(RegisterType::kFloat32, WordOrder::kBadc, {0xC03F, 0x0000}), 1.5);
  EXPECT_EQ(raw(RegisterType::kFloat32, WordOrder::kDcba, {0x0000, 0xC03F}), 1.5);
}

// Our order names must mean what libmodbus's modbus_get_float_<order> means.
TEST(ModbusCodec, Float32AgreesWithLibmodbus) {
  const Words samples[] = {{0x4048, 0xF5C3}, {0xC2F6, 0xE979}, {0x0001, 0x8000}, {0x1234, 0x5678}};
  for (const Words& w : samples) {
    EXPECT_EQ(raw(RegisterType::kFloat32, WordOrder::kAbcd, w), modbus_get_float_abcd(w.data()));
    EXPECT_EQ(raw(RegisterType::kFloat32, WordOrder::kBadc, w), modbus_get_float_badc(w.data()));
    EXPECT_EQ(raw(RegisterType::kFloat32, WordOrder::kCdab, w), modbus_get_float_cdab(w.data()));
    EXPECT_EQ(raw(RegisterType::kFloat32, WordOrder::kDcba, w), modbus_get_float_dcba(w.data()));
  }
}

TEST(ModbusCodec, Int32AndUint32EveryWordOrder) {
  // 0x01020304 = 16909060
  const OrderCase positive[] = {{WordOrder::kAbcd, {0x0102, 0x0304}},
                                {WordOrder::kBadc, {0x0201, 0x0403}},
                                {WordOrder::kCdab, {0x0304, 0x0102}},
                                {WordOrder::kDcba, {0x0403, 0x0201}}};
  for (const auto& c : positive) {
    EXPECT_EQ(raw(RegisterType::kInt32, c.order, c.words), 16909060.0);
    EXPECT_EQ(raw(RegisterType::kUint32, c.order, c.words), 16909060.0);
  }
  // -2 = 0xFFFFFFFE: sign extension for int32, the same bits as 4294967294 for uint32.
  const OrderCase minus_two[] = {{WordOrder::kAbcd, {0xFFFF, 0xFFFE}},
                                 {WordOrder::kBadc, {0xFFFF, 0xFEFF}},
                                 {WordOrder::kCdab, {0xFFFE, 0xFFFF}},
                                 {WordOrder::kDcba, {0xFEFF, 0xFFFF}}};
  for (const auto& c : minus_two) {
    EXPECT_EQ(raw(RegisterType::kInt32, c.order, c.words), -2.0) << wordOrderName(c.order);
    EXPECT_EQ(raw(RegisterType::kUint32, c.order, c.words), 4294967294.0);
  }
}

TEST(ModbusCodec, ExtremeIntegers) {
  EXPECT_EQ(raw(RegisterType::kInt32, WordOrder::kAbcd, {0x8000, 0x0000}), -2147483648.0);
  EXPECT_EQ(raw(RegisterType::kInt32, WordOrder::kAbcd, {0x7FFF, 0xFFFF}), 2147483647.0);
  EXPECT_EQ(raw(RegisterType::kUint32, WordOrder::kAbcd, {0xFFFF, 0xFFFF}), 4294967295.0);
  EXPECT_EQ(raw(RegisterType::kInt32, WordOrder::kCdab, {0x0000, 0x8000}), -2147483648.0);
  EXPECT_EQ(raw(RegisterType::kInt16, WordOrder::kAbcd, {0x8000}), -32768.0);
  EXPECT_EQ(raw(RegisterType::kInt16, WordOrder::kAbcd, {0xFFFF}), -1.0);
  EXPECT_EQ(raw(RegisterType::kInt16, WordOrder::kAbcd, {0x7FFF}), 32767.0);
  EXPECT_EQ(raw(RegisterType::kUint16, WordOrder::kAbcd, {0xFFFF}), 65535.0);
  EXPECT_EQ(raw(RegisterType::kUint16, WordOrder::kAbcd, {0x8000}), 32768.0);
}

TEST(ModbusCodec, ExtremeFloats) {
  EXPECT_EQ(raw(RegisterType::kFloat32, WordOrder::kAbcd, {0x7F7F, 0xFFFF}),
            static_cast<double>(std::numeric_limits<float>::max()));
  EXPECT_EQ(raw(RegisterType::kFloat32, WordOrder::kAbcd, {0x0000, 0x0001}),
            static_cast<double>(std::numeric_limits<float>::denorm_min()));
  EXPECT_EQ(raw(RegisterType::kFloat32, WordOrder::kAbcd, {0x8000, 0x0000}), 0.0);
  EXPECT_TRUE(std::signbit(raw(RegisterType::kFloat32, WordOrder::kAbcd, {0x8000, 0x0000})));
  EXPECT_EQ(raw(RegisterType::kFloat32, WordOrder::kAbcd, {0xC2F6, 0xE979}),
            static_cast<double>(-123.456f));
}

TEST(ModbusCodec, ScaleMultipliesTheRawValue) {
  const Words minus200 = {0xFF38};
  EXPECT_DOUBLE_EQ(decodeField(field(RegisterType::kInt16, WordOrder::kAbcd, 0.001), minus200, "j"),
                   -0.2);
  const Words w123456 = {0x0001, 0xE240};  // 123456
  EXPECT_DOUBLE_EQ(decodeField(field(RegisterType::kInt32, WordOrder::kAbcd, 0.001), w123456, "j"),
                   123.456);
  const Words w1_5 = {0x3FC0, 0x0000};
  EXPECT_EQ(decodeField(field(RegisterType::kFloat32, WordOrder::kAbcd, -2.0), w1_5, "j"), -3.0);
}

TEST(ModbusCodec, NanAndInfinityAreErrorsNamingTheField) {
  const Words nan = {0x7FC0, 0x0000};
  const Words inf = {0x7F80, 0x0000};
  const Words minus_inf = {0x0000, 0xFF80};  // cdab
  try {
    decodeField(field(RegisterType::kFloat32), nan, "joints.A");
    FAIL() << "NaN decoded";
  } catch (const RegisterValueError& e) {
    EXPECT_STREQ(e.what(), "joints.A: the controller sent NaN");
  }
  EXPECT_THROW(decodeField(field(RegisterType::kFloat32), inf, "joints.X"), RegisterValueError);
  EXPECT_THROW(decodeField(field(RegisterType::kFloat32, WordOrder::kCdab), minus_inf, "x"),
               RegisterValueError);
  // float max times a scale beyond double range is infinite too
  const Words fmax = {0x7F7F, 0xFFFF};
  EXPECT_THROW(decodeField(field(RegisterType::kFloat32, WordOrder::kAbcd, 1e300), fmax, "x"),
               RegisterValueError);
}

TEST(ModbusCodec, EncodeWritesTheHandMadeWords) {
  Words w(2);
  encodeField(field(RegisterType::kFloat32, WordOrder::kBadc), 1.5, w, "x");
  EXPECT_EQ(w, (Words{0xC03F, 0x0000}));
  encodeField(field(RegisterType::kFloat32, WordOrder::kDcba), 3.14, w, "x");
  EXPECT_EQ(w, (Words{0xC3F5, 0x4840}));
  encodeField(field(RegisterType::kInt32, WordOrder::kCdab), -2, w, "x");
  EXPECT_EQ(w, (Words{0xFFFE, 0xFFFF}));
  encodeField(field(RegisterType::kUint32, WordOrder::kBadc), 16909060, w, "x");
  EXPECT_EQ(w, (Words{0x0201, 0x0403}));
  encodeField(field(RegisterType::kInt32, WordOrder::kAbcd, 0.001), 123.456, w, "x");
  EXPECT_EQ(w, (Words{0x0001, 0xE240}));
  Words one(1);
  encodeField(field(RegisterType::kInt16), -32768, one, "x");
  EXPECT_EQ(one[0], 0x8000);
  encodeField(field(RegisterType::kInt16, WordOrder::kAbcd, 0.5), -1.25, one, "x");
  EXPECT_EQ(one[0], 0xFFFD);  // -2.5 rounds half away from zero to -3
  encodeField(field(RegisterType::kUint16), 65535, one, "x");
  EXPECT_EQ(one[0], 0xFFFF);
}

TEST(ModbusCodec, EncodeRefusesWhatDoesNotFit) {
  Words one(1);
  Words two(2);
  EXPECT_THROW(encodeField(field(RegisterType::kUint16), 65536, one, "x"), RegisterValueError);
  EXPECT_THROW(encodeField(field(RegisterType::kUint16), -1, one, "x"), RegisterValueError);
  EXPECT_THROW(encodeField(field(RegisterType::kInt16), 32768, one, "x"), RegisterValueError);
  EXPECT_THROW(encodeField(field(RegisterType::kInt32), 2147483648.0, two, "x"),
               RegisterValueError);
  EXPECT_THROW(encodeField(field(RegisterType::kUint32), 4294967296.0, two, "x"),
               RegisterValueError);
  EXPECT_THROW(encodeField(field(RegisterType::kFloat32), 1e39, two, "x"), RegisterValueError);
  EXPECT_THROW(encodeField(field(RegisterType::kFloat32), NAN, two, "x"), RegisterValueError);
}

TEST(ModbusCodec, RoundTripEveryTypeAndOrder) {
  const WordOrder orders[] = {WordOrder::kAbcd, WordOrder::kBadc, WordOrder::kCdab,
                              WordOrder::kDcba};
  for (WordOrder o : orders) {
    for (std::uint32_t bits : {0u, 1u, 0x01020304u, 0x80000000u, 0xFFFFFFFFu, 0x7F7FFFFFu}) {
      std::uint16_t a = 0;
      std::uint16_t b = 0;
      splitWords(bits, o, a, b);
      EXPECT_EQ(joinWords(a, b, o), bits);
    }
    Words w(2);
    for (double v : {-1e6, -0.5, 0.0, 12.25, 3.0e5}) {
      encodeField(field(RegisterType::kFloat32, o), v, w, "x");
      EXPECT_EQ(decodeField(field(RegisterType::kFloat32, o), w, "x"), v);
      encodeField(field(RegisterType::kInt32, o, 0.25), v, w, "x");
      EXPECT_EQ(decodeField(field(RegisterType::kInt32, o, 0.25), w, "x"), v);
    }
  }
}

ModbusMap fiveAxisMap() {
  return defaultModbusMap(kin::presets::acTrunnion());
}

TEST(ModbusMapLayout, DefaultMapOfAFiveAxisMachine) {
  const ModbusMap map = fiveAxisMap();
  ASSERT_EQ(map.joints.size(), 5u);
  const char* names[] = {"X", "Y", "Z", "A", "C"};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(map.joints[i].name, names[i]);
    EXPECT_EQ(map.joints[i].field.address, static_cast<int>(2 * i));
    EXPECT_EQ(map.joints[i].field.type, RegisterType::kFloat32);
    EXPECT_EQ(map.joints[i].field.word_order, WordOrder::kAbcd);
  }
  EXPECT_EQ(map.tool->address, 10);
  EXPECT_EQ(map.tool->type, RegisterType::kUint16);
  EXPECT_EQ(map.spindle_on->address, 11);
  EXPECT_EQ(map.line->address, 12);
  EXPECT_EQ(map.line->type, RegisterType::kUint32);
  EXPECT_EQ(registerSpan(map), 14);
  const kin::Machine ac = kin::presets::acTrunnion();
  EXPECT_TRUE(validateModbusMap(map, &ac).empty());
  const auto blocks = planReads(map);
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_EQ(blocks[0].start, 0);
  EXPECT_EQ(blocks[0].count, 14);
}

TEST(ModbusMapLayout, SampleRoundTripThroughARegisterImage) {
  const ModbusMap map = fiveAxisMap();
  ModbusSample in;
  in.joints[gcode::kX] = 12.5;
  in.joints[gcode::kY] = -3.25;
  in.joints[gcode::kZ] = 300;
  in.joints[gcode::kA] = -90;
  in.joints[gcode::kC] = 359.75;
  in.tool = 7;
  in.spindle_on = true;
  in.line = 70000;
  Words image(14);
  encodeSample(map, in, image);
  EXPECT_EQ(image[0], 0x4148);  // 12.5f = 0x41480000
  EXPECT_EQ(image[10], 7);
  EXPECT_EQ(image[11], 1);
  EXPECT_EQ(image[12], 0x0001);  // 70000 = 0x00011170
  EXPECT_EQ(image[13], 0x1170);
  const ModbusSample out = decodeSample(map, planReads(map), {image});
  for (gcode::Axis a : {gcode::kX, gcode::kY, gcode::kZ, gcode::kA, gcode::kC}) {
    EXPECT_EQ(out.joints[a], in.joints[a]);
  }
  EXPECT_EQ(out.joint_mask, 0b101111u);
  EXPECT_EQ(out.tool, 7);
  EXPECT_EQ(out.spindle_on, true);
  EXPECT_EQ(out.line, 70000);
  Words too_short(13);
  EXPECT_THROW(encodeSample(map, in, too_short), RegisterValueError);
}

TEST(ModbusMapLayout, ToolAndLineMustBeWholeNumbers) {
  ModbusMap map = fiveAxisMap();
  map.tool->type = RegisterType::kInt16;
  Words image(14);
  image[10] = 0xFFFF;  // tool -1
  try {
    decodeSample(map, planReads(map), {image});
    FAIL() << "negative tool decoded";
  } catch (const RegisterValueError& e) {
    EXPECT_THAT(e.what(), HasSubstr("tool: the controller sent -1"));
  }
  map.tool->type = RegisterType::kUint16;
  map.tool->scale = 0.5;
  image[10] = 3;  // 1.5
  EXPECT_THROW(decodeSample(map, planReads(map), {image}), RegisterValueError);
}

RegisterField at(int address, RegisterType type = RegisterType::kFloat32) {
  return {address, type};
}

TEST(ModbusMapLayout, SparseMapsReadInTheFewestBlocks) {
  ModbusMap map;
  map.host = "h";
  map.joints = {{"X", gcode::kX, at(0)}, {"Y", gcode::kY, at(200)}, {"Z", gcode::kZ, at(210)}};
  map.line = at(400, RegisterType::kUint32);
  map.tool = at(205, RegisterType::kUint16);
  const auto blocks = planReads(map);
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_EQ(blocks[0].start, 0);
  EXPECT_EQ(blocks[0].count, 2);
  EXPECT_EQ(blocks[1].start, 200);
  EXPECT_EQ(blocks[1].count, 12);
  EXPECT_EQ(blocks[2].start, 400);
  EXPECT_EQ(blocks[2].count, 2);
  // 125 registers is one read, 126 two.
  map.joints = {{"X", gcode::kX, at(0)}, {"Y", gcode::kY, at(123)}};
  map.tool.reset();
  map.line.reset();
  ASSERT_EQ(planReads(map).size(), 1u);
  EXPECT_EQ(planReads(map)[0].count, 125);
  map.joints[1].field.address = 124;
  ASSERT_EQ(planReads(map).size(), 2u);
  EXPECT_EQ(planReads(map)[1].start, 124);
  // The plan decodes: words land where the fields are.
  std::vector<Words> words = {Words(2), Words(2)};
  words[1] = {0x3FC0, 0x0000};
  EXPECT_EQ(decodeSample(map, planReads(map), words).joints[gcode::kY], 1.5);
}

std::vector<std::string> issueFields(const ModbusMap& map, const kin::Machine* m = nullptr) {
  std::vector<std::string> out;
  for (const auto& i : validateModbusMap(map, m)) out.push_back(i.field + ": " + i.message);
  return out;
}

TEST(ModbusMapValidation, OverlapsAndAddressRange) {
  ModbusMap map;
  map.host = "h";
  map.joints = {{"X", gcode::kX, at(0)}, {"Y", gcode::kY, at(1)}};
  EXPECT_THAT(issueFields(map),
              ::testing::ElementsAre("joints.Y.address: registers 1..2 overlap joints.X "
                                     "(registers 0..1)"));
  map.joints[1].field.address = 65534;
  EXPECT_TRUE(issueFields(map).empty());
  map.joints[1].field.address = 65535;  // its second word would be 65536
  EXPECT_THAT(issueFields(map),
              ::testing::ElementsAre(
                  "joints.Y.address: registers 65535..65536 (a float32) is outside 0..65535"));
  map.joints[1].field = at(65535, RegisterType::kUint16);
  EXPECT_TRUE(issueFields(map).empty());
  map.joints[1].field.address = -1;
  EXPECT_THAT(issueFields(map), ::testing::ElementsAre(HasSubstr("joints.Y.address")));
  map.joints[1].field = at(2);
  map.line = at(3, RegisterType::kUint32);
  EXPECT_THAT(issueFields(map), ::testing::ElementsAre(HasSubstr("line.address: registers 3..4 "
                                                                 "overlap joints.Y")));
  map.tool = at(3, RegisterType::kUint16);  // one register: "overlaps"
  map.line->address = 5;
  EXPECT_THAT(issueFields(map), ::testing::ElementsAre("tool.address: register 3 overlaps "
                                                       "joints.Y (registers 2..3)"));
  map.tool.reset();
  map.line->address = 4;
  map.line->scale = 0.0;
  EXPECT_THAT(issueFields(map), ::testing::ElementsAre(HasSubstr("line.scale")));
}

TEST(ModbusMapValidation, SettingsRanges) {
  ModbusMap map = fiveAxisMap();
  map.poll_hz = 0.0;
  map.timeout_ms = 0;
  map.port = 70000;
  map.unit_id = 256;
  map.host = "";
  map.feed_hold.coil = 65536;
  EXPECT_THAT(issueFields(map),
              ::testing::ElementsAre(HasSubstr("host:"), HasSubstr("port:"), HasSubstr("unit_id:"),
                                     HasSubstr("poll_hz:"), HasSubstr("timeout_ms:"),
                                     HasSubstr("feed_hold.coil:")));
  map = fiveAxisMap();
  map.poll_hz = 1000.0;
  EXPECT_TRUE(issueFields(map).empty());
  map.poll_hz = 1000.5;
  EXPECT_EQ(issueFields(map).size(), 1u);
  map.poll_hz = NAN;
  EXPECT_EQ(issueFields(map).size(), 1u);
}

TEST(ModbusMapValidation, JointsAgainstTheMachine) {
  const kin::Machine three = kin::presets::threeAxisMill();
  ModbusMap map = fiveAxisMap();  // X Y Z A C
  EXPECT_THAT(issueFields(map, &three),
              ::testing::ElementsAre("joints.A: the machine has no joint A (it has XYZ)",
                                     "joints.C: the machine has no joint C (it has XYZ)"));
  map.joints.resize(2);  // X Y only
  EXPECT_THAT(issueFields(map, &three),
              ::testing::ElementsAre(HasSubstr("joint Z has no register")));
  map.joints.clear();
  EXPECT_THAT(issueFields(map), ::testing::Contains(HasSubstr("at least one joint")));
}

}  // namespace
}  // namespace mdhd::protocol
