#include "daemon/trace_sink.h"

#include <charconv>
#include <cmath>
#include <string>

#include "sim/gcode/error.h"
#include "sim/kinematics/joint_path.h"

namespace mdhd::cli {
namespace {

const char* typeName(gcode::MotionType t) {
  switch (t) {
    case gcode::MotionType::kRapid:
      return "rapid";
    case gcode::MotionType::kFeed:
      return "feed";
    case gcode::MotionType::kArc:
      return "arc";
  }
  return "?";
}

const char* planeName(gcode::Plane p) {
  switch (p) {
    case gcode::Plane::kXY:
      return "XY";
    case gcode::Plane::kXZ:
      return "XZ";
    case gcode::Plane::kYZ:
      return "YZ";
  }
  return "?";
}

void appendEscaped(std::string& out, const std::string& s) {
  out += '"';
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  out += '"';
}

}  // namespace

void appendNumber(std::string& out, double v) {
  double r = std::round(v * 1e9) / 1e9;
  if (r == 0.0) r = 0.0;  // no "-0"
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, r);
  out.append(buf, res.ptr);
}

void TraceSink::motion(const gcode::Motion& m) {
  const geom::Tool* tool = job_.findTool(m.tool);
  // A move the machine cannot make (a TCP pose through a singularity) is an error at
  // its block, with line and column, as `mdhd check` reports it.
  const kin::JointPath path = [&] {
    try {
      return kin::JointPath(kin_, m, tool != nullptr ? tool->length : 0.0);
    } catch (const kin::KinematicsError& e) {
      throw gcode::GcodeError(m.pos, std::string("cannot make this move: ") + e.what());
    }
  }();
  const kin::JointValues& q = path.endJoints();

  std::string line;
  line.reserve(160);
  line += "{\"line\":";
  line += std::to_string(m.pos.line);
  if (!m.pos.file.empty()) {
    line += ",\"file\":";
    appendEscaped(line, m.pos.file);
  }
  line += ",\"type\":\"";
  line += typeName(m.type);
  line += "\",\"joints\":{";
  bool first = true;
  for (const kin::Joint& joint : kin_.machine().joints) {
    const auto axis = kin::axisOfName(joint.name);
    if (!axis) continue;
    if (!first) line += ',';
    first = false;
    appendEscaped(line, joint.name);
    line += ':';
    appendNumber(line, q[*axis]);
  }
  line += "},\"tool\":";
  line += std::to_string(m.tool);
  if (m.type != gcode::MotionType::kRapid) {
    line += ",\"feed\":";
    appendNumber(line, m.feed);
  }
  if (m.type == gcode::MotionType::kArc) {
    line += ",\"center\":[";
    appendNumber(line, m.center[0]);
    line += ',';
    appendNumber(line, m.center[1]);
    line += "],\"plane\":\"";
    line += planeName(m.plane);
    line += "\",\"turns\":";
    line += std::to_string(m.turn);
  }
  if (m.tcp) line += ",\"tcp\":true";
  line += "}\n";
  out_ << line;
  ++motions_;
}

}  // namespace mdhd::cli
