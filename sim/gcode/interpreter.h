#pragma once
// The G-code interpreter: program text in, canonical motions and events out
// (to a MotionSink), streaming: memory does not grow with program length.
//
//   InterpreterConfig config;             // work offsets, home, tools, axes
//   Interpreter interp(config, sink);
//   interp.run(makeStreamSource(std::make_unique<std::ifstream>(path)));
//
// run() throws GcodeError (file, line, column, message) at the first rejected
// block; motions of the blocks before it have been delivered.
#include <array>
#include <memory>

#include "sim/gcode/block_executor.h"
#include "sim/gcode/interpreter_config.h"
#include "sim/gcode/parameters.h"
#include "sim/gcode/source.h"

namespace mdhd::gcode {

class Reader;

class Interpreter {
 public:
  Interpreter(InterpreterConfig config, MotionSink& sink);
  Interpreter(const Interpreter&) = delete;
  Interpreter& operator=(const Interpreter&) = delete;

  // Interprets a whole program (until end of file, '%', M2 or M30).
  void run(std::unique_ptr<LineSource> program);

  const InterpState& state() const { return executor_.state(); }
  const ParameterStore& parameters() const { return params_; }
  const AxisValues& machinePosition() const { return executor_.machinePosition(); }
  std::uint64_t blocksExecuted() const { return blocks_; }

 private:
  void publishParameters(bool offsets);

  BlockExecutor executor_;
  ParameterStore params_;
  const Reader* reader_ = nullptr;  // during run(): answers #<_line>, #<_call_level>
  std::uint64_t blocks_ = 0;
  int probe_published_ = 0;                           // probe_count last written to #5061..#5070
  static constexpr int kFirstOffsetParameter = 5161;  // #5161 .. #5390 (G59.3 rotation)
  std::array<double, 5390 - kFirstOffsetParameter + 1> published_offsets_;
};

}  // namespace mdhd::gcode
