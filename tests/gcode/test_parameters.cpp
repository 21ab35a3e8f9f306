#include "sim/gcode/parameters.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace mdhd::gcode {
namespace {

TEST(Parameters, NumberedStartAtZeroAndKeepValues) {
  ParameterStore p;
  EXPECT_EQ(p.get(1), 0.0);
  EXPECT_EQ(p.get(5601), 0.0);
  EXPECT_EQ(p.get(ParameterStore::kDebugEnable), 1.0);  // LinuxCNC's default: DEBUG shown
  p.set(5221, 12.5);
  EXPECT_EQ(p.get(5221), 12.5);
  EXPECT_THROW(p.get(0), std::out_of_range);
  EXPECT_THROW(p.set(5602, 1.0), std::out_of_range);
  EXPECT_TRUE(ParameterStore::validNumber(1));
  EXPECT_FALSE(ParameterStore::validNumber(0));
}

TEST(Parameters, CallLevelsSaveLocalsAndRestoreThem) {
  ParameterStore p;
  p.set(1, 11.0);
  p.set(30, 30.0);
  p.set(31, 31.0);
  p.setNamed("loc", 1.0);
  p.setNamed("_glob", 2.0);
  const double args[] = {7.0, 8.0};
  p.enterCall(args, 2);
  EXPECT_EQ(p.callLevel(), 1);
  EXPECT_EQ(p.get(1), 7.0);
  EXPECT_EQ(p.get(2), 8.0);
  EXPECT_EQ(p.get(30), 0.0);                     // no argument: 0
  EXPECT_EQ(p.get(31), 31.0);                    // #31 and up are global
  EXPECT_FALSE(p.findNamed("loc").has_value());  // locals belong to their level
  EXPECT_EQ(p.findNamed("_glob").value(), 2.0);
  p.setNamed("loc", 5.0);
  p.setNamed("_glob", 6.0);
  p.set(31, 32.0);
  p.leaveCall();
  EXPECT_EQ(p.callLevel(), 0);
  EXPECT_EQ(p.get(1), 11.0);
  EXPECT_EQ(p.get(30), 30.0);
  EXPECT_EQ(p.get(31), 32.0);
  EXPECT_EQ(p.findNamed("loc").value(), 1.0);
  EXPECT_EQ(p.findNamed("_glob").value(), 6.0);
  p.leaveCall();  // at level 0: nothing to leave
  EXPECT_EQ(p.callLevel(), 0);
}

TEST(Parameters, PredefinedHookIsReadOnlyAndFirst) {
  ParameterStore p;
  p.setNamed("_x", 99.0);  // a global of that name is shadowed by the hook
  p.setPredefined([](std::string_view name) -> std::optional<double> {
    if (name == "_x") return 4.5;
    if (name == "_metric") return 1.0;
    return std::nullopt;
  });
  EXPECT_EQ(p.findNamed("_x").value(), 4.5);
  EXPECT_EQ(p.findNamed("_metric").value(), 1.0);
  EXPECT_TRUE(p.isReadOnly("_x"));
  EXPECT_FALSE(p.isReadOnly("_mine"));
  EXPECT_FALSE(p.isReadOnly("x"));
  EXPECT_FALSE(p.findNamed("_y").has_value());
}

TEST(Parameters, ReturnValue) {
  ParameterStore p;
  EXPECT_EQ(p.findNamed("_value").value(), 0.0);
  EXPECT_EQ(p.findNamed("_value_returned").value(), 0.0);
  p.setReturnValue(3.25);
  EXPECT_EQ(p.findNamed("_value").value(), 3.25);
  EXPECT_EQ(p.findNamed("_value_returned").value(), 1.0);
  EXPECT_TRUE(p.isReadOnly("_value"));
  p.setReturnValue(std::nullopt);
  EXPECT_EQ(p.findNamed("_value").value(), 0.0);
  EXPECT_EQ(p.findNamed("_value_returned").value(), 0.0);
}

}  // namespace
}  // namespace mdhd::gcode
