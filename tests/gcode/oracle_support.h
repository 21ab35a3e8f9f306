#pragma once
// Shared by the oracle tests: running a program through the interpreter with
// the oracle's setup (machine at zero, G5x zero, tools from a .tbl file) and
// reading the rs274 traces (tests/data/gcode-oracle, see its README).
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/gcode/interpreter.h"
#include "sim/gcode/reader.h"
#include "sim/gcode/tool_table.h"

namespace mdhd::gcode::testing {

inline std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct RecordedMotion {
  MotionType type;
  std::string file;
  int line;
  AxisValues start, end;
  Plane plane;
  std::array<double, 2> center;
  int turn;
  double feed;
  bool comp;
  bool sync;  // G33/G33.1: feed is the pitch
};

class RecordingSink : public MotionSink {
 public:
  void motion(const Motion& m) override {
    motions.push_back({m.type, m.pos.file, m.pos.line, m.start, m.end, m.plane, m.center, m.turn,
                       m.feed, m.comp, m.spindle_sync});
  }
  void event(const Event& e) override { events.push_back(e); }
  std::vector<RecordedMotion> motions;
  std::vector<Event> events;
};

// A program run to its end or its first error, with what the tests look at. The
// interpreter stays alive so its parameters can be read afterwards.
struct ProgramRun {
  std::vector<RecordedMotion> motions;
  std::vector<Event> events;
  std::optional<GcodeError> error;
  InterpState state;
  std::shared_ptr<RecordingSink> sink;
  std::shared_ptr<Interpreter> interp;
  double param(int number) const { return interp->parameters().get(number); }
};

inline ProgramRun runProgram(const std::string& program, InterpreterConfig config) {
  ProgramRun r;
  r.sink = std::make_shared<RecordingSink>();
  r.interp = std::make_shared<Interpreter>(std::move(config), *r.sink);
  try {
    r.interp->run(makeStringSource(program));
  } catch (const GcodeError& e) {
    r.error = e;
  }
  r.motions = r.sink->motions;
  r.events = r.sink->events;
  r.state = r.interp->state();
  return r;
}

struct OracleRun {
  std::vector<RecordedMotion> motions;
  std::optional<GcodeError> error;
};

// Runs program `path` with tool table `tbl` (mm_per_unit 25.4 for inch tables);
// `probe_stop` is the probe model (none: probe moves run to their targets).
inline OracleRun runOracleProgram(const std::string& path, const std::string& tbl,
                                  double mm_per_unit,
                                  decltype(InterpreterConfig::probe_stop) probe_stop = {}) {
  InterpreterConfig config;
  config.probe_stop = std::move(probe_stop);
  config.tools = parseToolTable(readText(tbl), mm_per_unit);
  const std::string dir = path.substr(0, path.rfind('/'));
  config.subroutine_loader = makeDirectoryLoader({dir});
  RecordingSink sink;
  OracleRun run;
  try {
    Interpreter interp(config, sink);
    interp.run(makeStreamSource(std::make_unique<std::ifstream>(path, std::ios::binary)));
  } catch (const GcodeError& e) {
    run.error = e;
  }
  run.motions = std::move(sink.motions);
  return run;
}

}  // namespace mdhd::gcode::testing
