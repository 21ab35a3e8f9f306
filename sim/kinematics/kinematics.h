#pragma once
// Forward kinematics of a Machine (spec section 2): joint values -> where the
// tool and the workpiece are. Compiled once per machine (unit axes, the constant
// parts of each rotation); an evaluation allocates nothing.
#include <array>
#include <stdexcept>
#include <string>

#include <glm/mat3x3.hpp>

#include "sim/kinematics/machine.h"
#include "sim/kinematics/rigid.h"

namespace mdhd::kin {

class KinematicsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The tool in the workpiece frame W: the tip and the unit axis from the tip towards
// the spindle.
struct ToolPose {
  glm::dvec3 tip{0.0};
  glm::dvec3 axis{0.0, 0.0, 1.0};
};

// sin and cos of an angle in degrees; exact at multiples of 90 so that cardinal
// poses (A-90, B180) come out exact.
void sinCosDegrees(double degrees, double& s, double& c);

class Kinematics {
 public:
  // Throws KinematicsError naming the first problem when validateMachine finds any.
  explicit Kinematics(Machine machine);

  const Machine& machine() const { return machine_; }
  const glm::dvec3& spindleAxis() const { return spindle_axis_; }  // unit, tool frame

  bool hasAxis(gcode::Axis a) const { return joint_of_axis_[a] >= 0; }
  // Index into machine().joints of the joint for a letter, or -1.
  int jointOf(gcode::Axis a) const { return joint_of_axis_[a]; }
  const std::array<bool, gcode::kAxisCount>& axes() const { return axes_; }
  // X, Y and Z all exist and are linear: G43.4 can solve for them.
  bool hasXyz() const { return hasAxis(gcode::kX) && hasAxis(gcode::kY) && hasAxis(gcode::kZ); }

  // T_tool: the tool (gauge point) frame in the machine frame.
  Rigid toolChain(const JointValues& q) const { return compose(tool_, tool_count_, q); }
  // T_wp: the workpiece frame W in the machine frame.
  Rigid workpieceChain(const JointValues& q) const { return compose(wp_, wp_count_, q); }
  // T_wp^-1 * T_tool: maps tool-frame coordinates to W (holder and shank go with it).
  Rigid toolInWorkpiece(const JointValues& q) const {
    if (wp_count_ == 0) return toolChain(q);  // W is the machine frame
    return workpieceChain(q).inverse() * toolChain(q);
  }
  // The tip and axis in W of a tool of `length` (gauge point to tip).
  ToolPose toolPose(const JointValues& q, double length) const;

  // The tip in W at q and, as the columns of `jac`, how it moves per unit of the X, Y
  // and Z joints (zero columns for letters the machine lacks). With the other joints
  // fixed the tip is affine in X, Y, Z, so tip(q + dx) = tip + jac dx exactly.
  glm::dvec3 tipJacobian(const JointValues& q, double length, glm::dmat3& jac) const;

 private:
  // One joint of a chain with the parts of its transform that do not depend on q.
  struct ChainJoint {
    int axis = 0;  // index into JointValues
    bool rotary = false;
    glm::dvec3 unit{0.0};
    glm::dvec3 origin{0.0};
    glm::dmat3 outer{0.0};  // unit * unit^T
    glm::dmat3 cross{0.0};  // [unit]x
  };
  using Chain = std::array<ChainJoint, gcode::kAxisCount>;

  static ChainJoint compile(const Joint& joint);
  // `xyz`, when given, receives the base-frame direction of each of the chain's X, Y, Z.
  static Rigid compose(const Chain& chain, int count, const JointValues& q,
                       glm::dmat3* xyz = nullptr);
  static int fill(const Machine& m, const std::vector<int>& indices, Chain& chain);

  Machine machine_;
  glm::dvec3 spindle_axis_{0.0, 0.0, 1.0};
  std::array<int, gcode::kAxisCount> joint_of_axis_{};
  std::array<bool, gcode::kAxisCount> axes_{};
  Chain tool_{};
  Chain wp_{};
  int tool_count_ = 0;
  int wp_count_ = 0;
};

}  // namespace mdhd::kin
