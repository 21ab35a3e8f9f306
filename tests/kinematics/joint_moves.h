#pragma once
// Joint vectors and feed moves between them, for the kinematics tests.
#include "sim/gcode/motion.h"
#include "sim/kinematics/machine.h"

namespace mdhd::kin::test_support {

inline JointValues xyz(double x, double y, double z) {
  return {x, y, z, 0, 0, 0, 0, 0, 0};
}

inline gcode::Motion move(JointValues a, JointValues b) {
  gcode::Motion m;
  m.type = gcode::MotionType::kFeed;
  m.start = a;
  m.end = b;
  return m;
}

}  // namespace mdhd::kin::test_support
