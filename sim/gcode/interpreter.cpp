#include "sim/gcode/interpreter.h"

#include <limits>

#include "sim/gcode/reader.h"

namespace mdhd::gcode {

Interpreter::Interpreter(InterpreterConfig config, MotionSink& sink)
    : executor_(std::move(config), sink) {
  published_offsets_.fill(std::numeric_limits<double>::quiet_NaN());
  executor_.attachParameters(&params_);
  params_.setPredefined([this](std::string_view name) -> std::optional<double> {
    double v = 0.0;
    if (executor_.predefined(name, v)) return v;
    if (reader_ && name == "_line") return reader_->currentLine();
    if (reader_ && name == "_call_level") return reader_->callLevel();
    return std::nullopt;
  });
  publishParameters(true);
}

void Interpreter::run(std::unique_ptr<LineSource> program) {
  const InterpreterConfig& config = executor_.config();
  ReaderOptions options;
  options.block_delete = config.block_delete;
  options.each_line = config.each_line;
  Reader reader(std::move(program), params_, config.subroutine_loader, options);
  reader_ = &reader;
  struct Detach {
    const Reader*& r;
    ~Detach() { r = nullptr; }
  } detach{reader_};
  Block block;
  while (!executor_.ended() && reader.next(block)) {
    executor_.execute(block);
    ++blocks_;
    const BlockWords& w = executor_.lastWords();
    publishParameters(w.g[kGNonModal] >= 0 || w.g[kGCoordSystem] >= 0 || w.m[kMStop] >= 0);
  }
  executor_.finish(block);
}

void Interpreter::publishParameters(bool offsets) {
  const InterpState& s = executor_.state();
  const double unit = s.inch ? kMmPerInch : 1.0;
  // #5420..#5428: current position in program units (LinuxCNC).
  for (int a = 0; a < kAxisCount; ++a) {
    const bool rotary = a >= kA && a <= kC;
    params_.set(5420 + a, rotary ? s.current[a] : s.current[a] / unit);
  }
  params_.set(5400, s.tool);
  params_.set(5403, s.tool_length);
  const ToolEntry* tool = executor_.config().tools.find(s.tool);
  params_.set(5410, tool ? tool->diameter : 0.0);
  if (s.probe_count != probe_published_) {  // #5061..#5069 probe point, #5070 tripped
    probe_published_ = s.probe_count;
    for (int a = 0; a < kAxisCount; ++a) {
      const bool rotary = a >= kA && a <= kC;
      params_.set(5061 + a, rotary ? s.probe_point[a] : s.probe_point[a] / unit);
    }
    params_.set(5070, s.probe_tripped ? 1.0 : 0.0);
  }
  if (!offsets) return;
  // Offsets and stored positions in machine units (mm). Only values the block
  // changed are written, so a value the program wrote itself stays until the
  // interpreter reads it (see BlockExecutor::attachParameters).
  auto put = [this](int number, double value) {
    double& last = published_offsets_[static_cast<std::size_t>(number - kFirstOffsetParameter)];
    if (last == value) return;
    last = value;
    params_.set(number, value);
  };
  for (int a = 0; a < kAxisCount; ++a) {
    put(5161 + a, s.g28[a]);
    put(5181 + a, s.g30[a]);
    put(5211 + a, s.g92_saved[a]);
    for (int c = 0; c < kCoordSystems; ++c) put(5221 + 20 * c + a, s.g5x[c][a]);
  }
  for (int c = 0; c < kCoordSystems; ++c) put(5230 + 20 * c, s.rotation[c]);
  put(5210, s.g92_applied ? 1.0 : 0.0);
  put(5220, s.coord_system + 1);
}

}  // namespace mdhd::gcode
