// libFuzzer entry point for the G-code interpreter: any bytes as a program, run to
// the end on a 5-axis setup with two tools, every motion checked for finite values.
// A GcodeError is a proper rejection; any other exception, crash, hang or sanitizer
// report is a bug. Budgets (lines read, motions) keep a run short: a run over one is
// stopped as the service stops a long dry interpretation.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "sim/gcode/interpreter.h"

namespace {

struct Budget {};

class CheckingSink : public mdhd::gcode::MotionSink {
 public:
  void motion(const mdhd::gcode::Motion& m) override {
    // A motion the interpreter hands on must be usable: finite ends and feed.
    for (double v : m.start)
      if (!std::isfinite(v)) std::abort();
    for (double v : m.end)
      if (!std::isfinite(v)) std::abort();
    if (++motions_ > 20'000) throw Budget{};
  }

 private:
  int motions_ = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace mdhd::gcode;
  const std::string program(reinterpret_cast<const char*>(data), size);
  InterpreterConfig config;
  config.work_offsets[0] = {10.0, -20.0, 5.0};
  config.tools.add({1, 50.0, 6.0});
  config.tools.add({2, 80.0, 10.0});
  int lines = 0;
  config.each_line = [&lines] {
    if (++lines > 20'000) throw Budget{};
  };
  // Every external subroutine is the program itself, so loading is exercised.
  config.subroutine_loader = [&program](std::string_view) { return makeStringSource(program); };
  CheckingSink sink;
  try {
    Interpreter interp(config, sink);
    interp.run(makeStringSource(program));
  } catch (const GcodeError&) {
  } catch (const Budget&) {
  }
  return 0;
}
